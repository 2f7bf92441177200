#include "tracking/head_pose.hpp"

namespace cupola {

const char* head_source_name(HeadSource s) {
    switch (s) {
        case HeadSource::Default:
            return "default";
        case HeadSource::Tracked:
            return "tracked";
        case HeadSource::Held:
            return "held";
        case HeadSource::Control:
            return "control";
    }
    return "unknown";
}

}  // namespace cupola
