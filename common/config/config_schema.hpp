#pragma once
// The JSON Schemas of the configuration files (configs/schema/*.schema.json, draft-07), compiled
// into the program. They are the one declaration of every field: its default, range or allowed
// values and its documentation. The readers take defaults and ranges from them (JsonReader's
// declared_* accessors), tools/config_docs.py writes docs/CONFIG.md from them, and tests validate
// the shipped configs against them with valijson.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace cupola {

// "cluster", "scene", "show" or "devices"; throws std::out_of_range for another name.
const nlohmann::json& config_schema(const std::string& name);
const std::vector<std::string>& config_schema_names();

}  // namespace cupola
