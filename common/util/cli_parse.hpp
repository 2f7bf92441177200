#pragma once
// Command-line parsing shared by the programs that report bad arguments themselves: --help
// prints the usage (exit 0); a parse error prints "<program>: <what>" and a hint (exit 2).
// Header-only: the programs link CLI11, the common library does not.
#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <string>

namespace cupola {

// Parses; returns the exit code to stop with, or nothing to go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv, const std::string& program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << program << ": " << e.what() << "\nrun with --help for usage\n";
        return 2;
    }
    return std::nullopt;
}

}  // namespace cupola
