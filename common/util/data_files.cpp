#include "util/data_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "util/child_process.hpp"

// The install rules (cmake/Packaging.cmake) set the path from the installed programs to the
// installed data; a build without them still finds the source tree.
#ifndef CUPOLA_BIN_TO_DATA
#define CUPOLA_BIN_TO_DATA "../share/cupola"
#endif

namespace cupola {

namespace fs = std::filesystem;

std::string data_file(const std::string& relative) {
    std::vector<fs::path> candidates;
    if (const char* dir = std::getenv("CUPOLA_DATA_DIR"); dir && *dir) {
        candidates.push_back(fs::path(dir) / relative);
    } else {
        candidates.push_back(fs::path(executable_dir()) / CUPOLA_BIN_TO_DATA / "data" / relative);
        candidates.push_back(fs::path(CUPOLA_SOURCE_DIR) / "data" / relative);
    }
    std::string looked;
    for (const fs::path& c : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(c, ec)) return c.lexically_normal().string();
        looked += (looked.empty() ? "" : ", ") + c.lexically_normal().string();
    }
    throw std::runtime_error("data file " + relative + " not found (looked in " + looked +
                             (std::getenv("CUPOLA_DATA_DIR") ? ", from $CUPOLA_DATA_DIR)" : ")"));
}

}  // namespace cupola
