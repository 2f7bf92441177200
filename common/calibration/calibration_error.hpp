#pragma once
// The one error type of the calibration readers and writers: it names the file (and region) it is
// about and the field or part of that file that was wrong, so an operator can find it.
#include <stdexcept>
#include <string>

namespace cupola {

class CalibrationError : public std::runtime_error {
public:
    // what(): "FILE: FIELD: MESSAGE" (FIELD left out when empty).
    CalibrationError(std::string file, std::string field, const std::string& message);

    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    const std::string& message() const { return message_; }

private:
    std::string file_;
    std::string field_;
    std::string message_;
};

}  // namespace cupola
