#pragma once
// An error in a configuration, scene or show file, naming the file and the field at fault.
#include <stdexcept>
#include <string>

namespace cupola {

class ConfigError : public std::runtime_error {
public:
    ConfigError(std::string file, std::string field, const std::string& what)
        : std::runtime_error(file + ": " + (field.empty() ? std::string("(top level)") : field) + ": " + what),
          file_(std::move(file)),
          field_(std::move(field)) {}
    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }

private:
    std::string file_;
    std::string field_;
};

}  // namespace cupola
