// libFuzzer target cupola-fuzz-sky-figures: the constellation data reader
// (common/overlay/constellation_figures) under hostile input. Checked invariants (a violation
// aborts, which libFuzzer reports): the reader returns figures or throws std::runtime_error; every
// figure it returns has a label, lines of at least two points, rings of at least three, and unit
// directions. ASan/UBSan turn memory errors and UB into crashes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "overlay/constellation_figures.hpp"

using namespace cupola;

namespace {
[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
}

void check_unit(const glm::dvec3& d) {
    if (!(std::abs(glm::length(d) - 1.0) < 1e-9)) violated("a direction is not a unit vector");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        for (const ConstellationFigure& f : parse_constellation_figures(text, "fuzz.json")) {
            if (f.labels.empty()) violated("a figure without a label");
            for (const auto& l : f.labels) check_unit(l.dir);
            for (const auto& line : f.lines) {
                if (line.size() < 2) violated("a line of fewer than two points");
                for (const auto& p : line) check_unit(p);
            }
            for (const auto& ring : f.boundaries)
                if (ring.size() < 3) violated("a ring of fewer than three points");
        }
    } catch (const std::runtime_error&) {}
    return 0;
}
