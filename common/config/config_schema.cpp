#include "config/config_schema.hpp"

#include <map>
#include <stdexcept>

namespace cupola {

namespace {
// {"name", R"(text)"}, one per configs/schema/<name>.schema.json; written by common/CMakeLists.txt.
const std::map<std::string, const char*>& schema_texts() {
    static const std::map<std::string, const char*> texts = {
#include "config_schema_text.inc"
    };
    return texts;
}
}  // namespace

const std::vector<std::string>& config_schema_names() {
    static const std::vector<std::string> names = {"cluster", "scene", "show", "devices"};
    return names;
}

const nlohmann::json& config_schema(const std::string& name) {
    static const std::map<std::string, nlohmann::json> parsed = [] {
        std::map<std::string, nlohmann::json> out;
        for (const auto& [n, text] : schema_texts()) out[n] = nlohmann::json::parse(text);
        return out;
    }();
    const auto it = parsed.find(name);
    if (it == parsed.end()) throw std::out_of_range("no config schema named \"" + name + "\"");
    return it->second;
}

}  // namespace cupola
