#include "calibration/calibration_error.hpp"

#include <utility>

namespace cupola {

namespace {
std::string compose(const std::string& file, const std::string& field, const std::string& message) {
    return field.empty() ? file + ": " + message : file + ": " + field + ": " + message;
}
}  // namespace

CalibrationError::CalibrationError(std::string file, std::string field, const std::string& message)
    : std::runtime_error(compose(file, field, message)),
      file_(std::move(file)),
      field_(std::move(field)),
      message_(message) {}

}  // namespace cupola
