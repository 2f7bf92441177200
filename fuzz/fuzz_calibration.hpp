#pragma once
// Shared by the calibration fuzz targets (fuzz_mpcdi.cpp, fuzz_pfm.cpp, fuzz_bourke.cpp): the one
// rule they check besides ASan/UBSan, that a reader returns or throws CalibrationError, and that
// what it returns keeps projector_warp.hpp's shape.
#include <cstdio>
#include <cstdlib>

#include "calibration/projector_warp.hpp"

namespace cupola::fuzz {

[[noreturn]] inline void violated(const char* what) {
    std::fprintf(stderr, "calibration fuzz: invariant violated: %s\n", what);
    std::abort();
}

inline void check_warp(const ProjectorWarp& w) {
    if (w.raster_width < 1 || w.raster_height < 1) violated("raster size not positive");
    if (w.grid.columns < 2 || w.grid.rows < 2) violated("grid smaller than 2x2");
    if (w.grid.uv.size() != static_cast<size_t>(w.grid.columns) * w.grid.rows) violated("grid size");
    if (!w.grid.intensity.empty() && w.grid.intensity.size() != w.grid.uv.size()) violated("intensity size");
    for (const BlendMap* m : {&w.alpha, &w.beta})
        if (!m->empty() && m->value.size() != static_cast<size_t>(m->width) * m->height) violated("blend map size");
}

}  // namespace cupola::fuzz
