#include "util/cli_main.hpp"

#include <spdlog/cfg/env.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <cstdio>

#include "config/config_error.hpp"

namespace cupola {

void setup_logging(const std::string& program, bool verbose, bool quiet) {
    auto logger = spdlog::stderr_color_mt(program);
    spdlog::set_default_logger(logger);
    spdlog::set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
    spdlog::set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
    spdlog::cfg::load_env_levels();
}

int run_main(const std::string& program, const std::function<int()>& body) {
    try {
        return body();
    } catch (const ConfigError& e) {
        std::fprintf(stderr, "%s: configuration error: %s\n", program.c_str(), e.what());
        return 2;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
        return 1;
    }
}

}  // namespace cupola
