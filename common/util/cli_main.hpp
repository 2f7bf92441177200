#pragma once
// Shared start-up for the command-line programs: logging level from --verbose/--quiet and
// SPDLOG_LEVEL, and uniform reporting of errors ("<program>: <message>", exit 2 for bad input).
#include <spdlog/spdlog.h>

#include <functional>
#include <string>

namespace cupola {

// Runs body(), mapping exceptions to messages on stderr and exit codes:
// ConfigError and std::invalid_argument -> 2 (bad input), anything else -> 1.
int run_main(const std::string& program, const std::function<int()>& body);

void setup_logging(const std::string& program, bool verbose, bool quiet);

}  // namespace cupola
