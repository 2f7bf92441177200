#include "support/headless_gl.hpp"

#include <cstdlib>
#include <filesystem>

namespace cupola::test {

EglContext& headless_gl(const std::string& cache_tag) {
    static EglContext* ctx = [&] {
        unsetenv("DISPLAY");
        unsetenv("WAYLAND_DISPLAY");
        if (!cache_tag.empty()) {
            const std::filesystem::path dir = std::filesystem::path(CUPOLA_TEST_TMP) / (cache_tag + "_cache");
            std::filesystem::create_directories(dir);
            setenv("CUPOLA_CACHE_DIR", dir.c_str(), 1);
        }
        return new EglContext(-1);
    }();
    return *ctx;
}

}  // namespace cupola::test
