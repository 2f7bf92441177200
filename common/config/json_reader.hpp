#pragma once
// Strict reader over one JSON object: every access names its field path, every unknown key is an
// error, every type or range mistake throws ConfigError(file, "a.b[2].c", what was wrong).
// A reader made with a schema (config/config_schema.hpp: configs/schema/*.schema.json) hands the
// matching sub-schema to its children, and its declared_* accessors take a field's range, allowed
// values, default and whether it is required from that declaration, so each is written once.
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "config/config_error.hpp"

namespace cupola {

class JsonReader {
public:
    JsonReader(const nlohmann::json& value, std::string file, std::string path);
    // A reader of a whole document declared by `schema` (a root schema, config_schema()).
    JsonReader(const nlohmann::json& value, std::string file, const nlohmann::json* schema);

    // Parses a whole file; a syntax error names the file, line and column.
    static nlohmann::json parse_file(const std::string& file);

    bool has(const std::string& key) const;
    JsonReader child(const std::string& key) const;  // required object
    std::optional<JsonReader> optional_child(const std::string& key) const;
    // An optional object whose absence reads as {}: every field in it takes its declared default.
    JsonReader section(const std::string& key) const;
    std::vector<JsonReader> array(const std::string& key) const;  // required array of objects

    double number(const std::string& key) const;
    double number(const std::string& key, double fallback) const;
    double number_in(const std::string& key, double lo, double hi) const;
    double number_in(const std::string& key, double lo, double hi, double fallback) const;
    long long integer_in(const std::string& key, long long lo, long long hi) const;
    long long integer_in(const std::string& key, long long lo, long long hi, long long fallback) const;
    bool boolean(const std::string& key, bool fallback) const;
    std::string string(const std::string& key) const;
    std::string string(const std::string& key, const std::string& fallback) const;
    std::string one_of(const std::string& key, const std::vector<std::string>& choices) const;
    std::string one_of(const std::string& key, const std::vector<std::string>& choices,
                       const std::string& fallback) const;
    std::vector<std::string> strings(const std::string& key, const std::vector<std::string>& fallback) const;
    glm::dvec3 dvec3(const std::string& key) const;
    std::optional<glm::dvec3> optional_dvec3(const std::string& key) const;

    // From the schema: range (minimum/maximum), allowed values (enum), default, required. The
    // overloads with a fallback are for defaults the schema cannot state (computed ones).
    double declared_number(const std::string& key) const;
    double declared_number(const std::string& key, double fallback) const;
    long long declared_integer(const std::string& key) const;
    long long declared_integer(const std::string& key, long long fallback) const;
    long long required_integer(const std::string& key) const;  // required here, whatever the schema says
    std::pair<double, double> declared_range(const std::string& key) const;
    bool declared_boolean(const std::string& key) const;
    std::string declared_string(const std::string& key) const;
    std::string declared_choice(const std::string& key) const;
    std::vector<std::string> declared_choices(const std::string& key) const;  // enum (of items)
    // The declaration of `key` ($ref resolved); throws std::logic_error when the schema lacks it.
    const nlohmann::json& declaration(const std::string& key) const;
    bool declared_required(const std::string& key) const;

    // Throws for the first key that no accessor asked for.
    void reject_unknown_keys() const;

    [[noreturn]] void fail(const std::string& key, const std::string& what) const;
    std::string field(const std::string& key) const;
    const std::string& file() const { return file_; }
    const std::string& path() const { return path_; }
    const nlohmann::json& raw() const { return value_; }

private:
    const nlohmann::json& get(const std::string& key) const;
    const nlohmann::json* sub_schema(const std::string& key, bool items) const;
    const nlohmann::json* find_keyword(const std::string& key, const std::string& word) const;
    const nlohmann::json& declared_default(const std::string& key) const;

    const nlohmann::json& value_;
    const nlohmann::json* schema_ = nullptr;  // this object's schema, or none
    const nlohmann::json* root_ = nullptr;    // the root schema ($ref targets)
    std::string file_;
    std::string path_;
    mutable std::set<std::string> seen_;
};

}  // namespace cupola
