#include "tracking/head_tracking_config.hpp"

namespace cupola {

const std::vector<std::string>& tracking_source_names() {
    static const std::vector<std::string> names = {"fixed", "dtrack"};
    return names;
}

const std::vector<std::string>& head_filter_names() {
    static const std::vector<std::string> names = {"none", "smooth", "predict"};
    return names;
}

}  // namespace cupola
