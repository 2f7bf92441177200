#pragma once
// Small helpers shared by the tests: scratch folders, repository paths, writing files. Linking
// them also sets CUPOLA_CACHE_DIR to <build>/test-tmp/atmosphere-cache for the whole process.
#include <string>
#include <utility>

namespace cupola::test {

// A fresh, empty folder under the build tree (removed and re-created), named `name` plus a short
// hash of the running test case, so parallel cases never share one: <build>/test-tmp/<name>-<hash>.
std::string scratch_dir(const std::string& name);

// Absolute path of a file in the source tree, e.g. source_path("configs/dome-4ch.json").
std::string source_path(const std::string& relative);

// Absolute path of a built program, e.g. bin_path("cupola-master").
std::string bin_path(const std::string& program);

void write_text(const std::string& path, const std::string& text);
std::string read_text(const std::string& path);

// Runs a shell command line; returns (exit status, or -1 if it did not exit normally; stdout).
std::pair<int, std::string> run_shell(const std::string& command);

}  // namespace cupola::test
