#pragma once
// The one headless EGL context of a test process (tests that render link cupola_render).
#include <string>

#include "gl/egl_context.hpp"

namespace cupola::test {

// Created on first use, on the first EGL device (as the slaves open it), with DISPLAY and
// WAYLAND_DISPLAY removed from the environment. With a cache tag, the first call also points
// CUPOLA_CACHE_DIR at <build>/test-tmp/<tag>_cache, created if missing and never emptied: ctest
// runs a program's cases as parallel processes, which share the tables one of them builds (a
// table file is keyed by its format version, parameters and quality, and one that cannot be read
// is rebuilt).
EglContext& headless_gl(const std::string& cache_tag = "");

}  // namespace cupola::test
