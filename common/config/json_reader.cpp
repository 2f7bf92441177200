#include "config/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cupola {

namespace {
std::string describe(const nlohmann::json& v) {
    std::string s = v.dump();
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}
}  // namespace

JsonReader::JsonReader(const nlohmann::json& value, std::string file, std::string path)
    : value_(value), file_(std::move(file)), path_(std::move(path)) {
    if (!value_.is_object()) throw ConfigError(file_, path_, "expected an object, got " + describe(value_));
}

JsonReader::JsonReader(const nlohmann::json& value, std::string file, const nlohmann::json* schema)
    : JsonReader(value, std::move(file), std::string()) {
    schema_ = schema;
    root_ = schema;
}

nlohmann::json JsonReader::parse_file(const std::string& file) {
    std::ifstream in(file);
    if (!in) throw ConfigError(file, "", "cannot open file");
    std::stringstream ss;
    ss << in.rdbuf();
    try {
        return nlohmann::json::parse(ss.str());
    } catch (const nlohmann::json::parse_error& e) {
        throw ConfigError(file, "", std::string("JSON syntax error: ") + e.what());
    } catch (const nlohmann::json::exception& e) {  // a number too large for a double, found by fuzz/
        throw ConfigError(file, "", std::string("JSON error: ") + e.what());
    }
}

std::string JsonReader::field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void JsonReader::fail(const std::string& key, const std::string& what) const {
    throw ConfigError(file_, field(key), what);
}

bool JsonReader::has(const std::string& key) const {
    seen_.insert(key);
    return value_.contains(key) && !value_.at(key).is_null();
}

const nlohmann::json& JsonReader::get(const std::string& key) const {
    seen_.insert(key);
    if (!value_.contains(key)) fail(key, "missing required field");
    return value_.at(key);
}

JsonReader JsonReader::child(const std::string& key) const {
    const auto& v = get(key);
    if (!v.is_object()) fail(key, "expected an object, got " + describe(v));
    JsonReader out(v, file_, field(key));
    out.schema_ = sub_schema(key, false);
    out.root_ = root_;
    return out;
}

std::optional<JsonReader> JsonReader::optional_child(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    return child(key);
}

JsonReader JsonReader::section(const std::string& key) const {
    static const nlohmann::json empty = nlohmann::json::object();
    if (has(key)) return child(key);
    JsonReader out(empty, file_, field(key));
    out.schema_ = sub_schema(key, false);
    out.root_ = root_;
    return out;
}

std::vector<JsonReader> JsonReader::array(const std::string& key) const {
    const auto& v = get(key);
    if (!v.is_array()) fail(key, "expected an array, got " + describe(v));
    std::vector<JsonReader> out;
    for (size_t i = 0; i < v.size(); ++i) {
        std::string p = field(key) + "[" + std::to_string(i) + "]";
        if (!v[i].is_object()) throw ConfigError(file_, p, "expected an object, got " + describe(v[i]));
        out.emplace_back(v[i], file_, p);
        out.back().schema_ = sub_schema(key, true);
        out.back().root_ = root_;
    }
    return out;
}

double JsonReader::number(const std::string& key) const {
    const auto& v = get(key);
    if (!v.is_number()) fail(key, "expected a number, got " + describe(v));
    double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "expected a finite number");
    return d;
}

double JsonReader::number(const std::string& key, double fallback) const { return has(key) ? number(key) : fallback; }

double JsonReader::number_in(const std::string& key, double lo, double hi) const {
    double d = number(key);
    if (d < lo || d > hi) {
        std::ostringstream os;
        os << "value " << d << " is outside the allowed range [" << lo << ", " << hi << "]";
        fail(key, os.str());
    }
    return d;
}

double JsonReader::number_in(const std::string& key, double lo, double hi, double fallback) const {
    return has(key) ? number_in(key, lo, hi) : fallback;
}

long long JsonReader::integer_in(const std::string& key, long long lo, long long hi) const {
    const auto& v = get(key);
    if (!v.is_number_integer()) fail(key, "expected an integer, got " + describe(v));
    long long n = v.get<long long>();
    if (n < lo || n > hi) {
        fail(key, "value " + std::to_string(n) + " is outside the allowed range [" + std::to_string(lo) + ", " +
                      std::to_string(hi) + "]");
    }
    return n;
}

long long JsonReader::integer_in(const std::string& key, long long lo, long long hi, long long fallback) const {
    return has(key) ? integer_in(key, lo, hi) : fallback;
}

bool JsonReader::boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const auto& v = get(key);
    if (!v.is_boolean()) fail(key, "expected true or false, got " + describe(v));
    return v.get<bool>();
}

std::string JsonReader::string(const std::string& key) const {
    const auto& v = get(key);
    if (!v.is_string()) fail(key, "expected a string, got " + describe(v));
    return v.get<std::string>();
}

std::string JsonReader::string(const std::string& key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
}

std::string JsonReader::one_of(const std::string& key, const std::vector<std::string>& choices) const {
    std::string s = string(key);
    for (const auto& c : choices)
        if (c == s) return s;
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    fail(key, "\"" + s + "\" is not one of: " + list);
}

std::string JsonReader::one_of(const std::string& key, const std::vector<std::string>& choices,
                               const std::string& fallback) const {
    return has(key) ? one_of(key, choices) : fallback;
}

std::vector<std::string> JsonReader::strings(const std::string& key, const std::vector<std::string>& fallback) const {
    if (!has(key)) return fallback;
    const auto& v = get(key);
    if (!v.is_array()) fail(key, "expected an array of strings, got " + describe(v));
    std::vector<std::string> out;
    for (size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_string())
            throw ConfigError(file_, field(key) + "[" + std::to_string(i) + "]",
                              "expected a string, got " + describe(v[i]));
        out.push_back(v[i].get<std::string>());
    }
    return out;
}

glm::dvec3 JsonReader::dvec3(const std::string& key) const {
    const auto& v = get(key);
    if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers, got " + describe(v));
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i) {
        if (!v[i].is_number()) fail(key, "expected an array of 3 numbers, got " + describe(v));
        out[i] = v[i].get<double>();
        if (!std::isfinite(out[i])) fail(key, "expected finite numbers");
    }
    return out;
}

std::optional<glm::dvec3> JsonReader::optional_dvec3(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    return dvec3(key);
}

// ---- declarations from the schema ------------------------------------------------------------

namespace {
const nlohmann::json& resolve_ref(const nlohmann::json& node, const nlohmann::json* root) {
    if (!root || !node.is_object() || !node.contains("$ref")) return node;
    const std::string ref = node.at("$ref").get<std::string>();  // "#/definitions/name"
    return root->at(nlohmann::json::json_pointer(ref.substr(1)));
}
}  // namespace

const nlohmann::json* JsonReader::sub_schema(const std::string& key, bool items) const {
    if (!schema_ || !schema_->contains("properties") || !schema_->at("properties").contains(key)) return nullptr;
    const nlohmann::json* node = &resolve_ref(schema_->at("properties").at(key), root_);
    if (items) node = node->contains("items") ? &resolve_ref(node->at("items"), root_) : nullptr;
    return node;
}

const nlohmann::json& JsonReader::declaration(const std::string& key) const {
    if (!schema_ || !schema_->contains("properties") || !schema_->at("properties").contains(key))
        throw std::logic_error("the schema declares no field " + field(key));
    return schema_->at("properties").at(key);
}

// A keyword of the declaration itself, else of the definition its $ref names.
const nlohmann::json* JsonReader::find_keyword(const std::string& key, const std::string& word) const {
    const nlohmann::json& d = declaration(key);
    if (d.contains(word)) return &d.at(word);
    const nlohmann::json& r = resolve_ref(d, root_);
    return r.contains(word) ? &r.at(word) : nullptr;
}

bool JsonReader::declared_required(const std::string& key) const {
    declaration(key);
    if (!schema_->contains("required")) return false;
    const auto& req = schema_->at("required");
    return std::find(req.begin(), req.end(), key) != req.end();
}

const nlohmann::json& JsonReader::declared_default(const std::string& key) const {
    const nlohmann::json* d = find_keyword(key, "default");
    if (!d) throw std::logic_error("the schema gives no default for the optional field " + field(key));
    return *d;
}

std::pair<double, double> JsonReader::declared_range(const std::string& key) const {
    const nlohmann::json *lo = find_keyword(key, "minimum"), *hi = find_keyword(key, "maximum");
    if (!lo || !hi) throw std::logic_error("the schema gives no range for " + field(key));
    return {lo->get<double>(), hi->get<double>()};
}

double JsonReader::declared_number(const std::string& key, double fallback) const {
    const auto [lo, hi] = declared_range(key);
    return number_in(key, lo, hi, fallback);
}

double JsonReader::declared_number(const std::string& key) const {
    const auto [lo, hi] = declared_range(key);
    if (declared_required(key)) return number_in(key, lo, hi);
    return number_in(key, lo, hi, declared_default(key).get<double>());
}

// Integer bounds are exact in a double up to 2^53, far beyond every declared range.
long long JsonReader::required_integer(const std::string& key) const {
    const auto [lo, hi] = declared_range(key);
    return integer_in(key, static_cast<long long>(lo), static_cast<long long>(hi));
}

long long JsonReader::declared_integer(const std::string& key, long long fallback) const {
    const auto [lo, hi] = declared_range(key);
    return integer_in(key, static_cast<long long>(lo), static_cast<long long>(hi), fallback);
}

long long JsonReader::declared_integer(const std::string& key) const {
    if (declared_required(key)) return required_integer(key);
    return declared_integer(key, declared_default(key).get<long long>());
}

bool JsonReader::declared_boolean(const std::string& key) const {
    return boolean(key, declared_default(key).get<bool>());
}

std::string JsonReader::declared_string(const std::string& key) const {
    if (declared_required(key)) return string(key);
    return string(key, declared_default(key).get<std::string>());
}

std::vector<std::string> JsonReader::declared_choices(const std::string& key) const {
    const nlohmann::json* e = find_keyword(key, "enum");
    if (!e) {
        const nlohmann::json* items = find_keyword(key, "items");
        if (items) e = resolve_ref(*items, root_).contains("enum") ? &resolve_ref(*items, root_).at("enum") : nullptr;
    }
    if (!e) throw std::logic_error("the schema gives no allowed values for " + field(key));
    return e->get<std::vector<std::string>>();
}

std::string JsonReader::declared_choice(const std::string& key) const {
    if (declared_required(key)) return one_of(key, declared_choices(key));
    return one_of(key, declared_choices(key), declared_default(key).get<std::string>());
}

void JsonReader::reject_unknown_keys() const {
    for (auto it = value_.begin(); it != value_.end(); ++it) {
        if (!seen_.count(it.key())) fail(it.key(), "unknown key (check the spelling; see docs/CONFIG.md)");
    }
}

}  // namespace cupola
