#include "support/test_support.hpp"

#include <sys/wait.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cupola::test {

namespace fs = std::filesystem;

namespace {
// Every test executable (and every process it starts) keeps the atmosphere's table cache in the
// build tree, never in the user's ~/.cache; a test may still point it elsewhere.
const bool kCacheInBuildTree = [] {
    setenv("CUPOLA_CACHE_DIR", (fs::path(CUPOLA_TEST_TMP) / "atmosphere-cache").c_str(), 1);
    return true;
}();
}  // namespace

namespace {
// ctest runs each case of a program as its own process, in parallel. Two cases that ask for the
// same folder name must not empty each other's folder, so the name gets a short suffix from the
// running case's full name (FNV-1a, 32 bits). It stays short: a Unix socket path is limited to
// 107 bytes, and some tests put the control socket in their folder.
std::string test_case_suffix() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    if (info == nullptr) return "";
    const std::string full = std::string(info->test_suite_name()) + "." + info->name();
    std::uint32_t h = 2166136261u;
    for (const unsigned char c : full) h = (h ^ c) * 16777619u;
    char buf[10];
    std::snprintf(buf, sizeof buf, "-%08x", h);
    return buf;
}
}  // namespace

std::string scratch_dir(const std::string& name) {
    fs::path p = fs::path(CUPOLA_TEST_TMP) / (name + test_case_suffix());
    fs::remove_all(p);
    fs::create_directories(p);
    return p.string();
}

std::string source_path(const std::string& relative) { return (fs::path(CUPOLA_SOURCE_DIR) / relative).string(); }

std::string bin_path(const std::string& program) { return (fs::path(CUPOLA_BIN_DIR) / program).string(); }

void write_text(const std::string& path, const std::string& text) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write " + path);
    out << text;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::pair<int, std::string> run_shell(const std::string& command) {
    std::string out;
    FILE* p = popen(command.c_str(), "r");
    if (!p) return {-1, ""};
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace cupola::test
