#pragma once
// The output's present (docs/SWAP_LOCK.md): shows the frame the slave holds and returns
// CLOCK_MONOTONIC ns just after the swap. A window or KMS output swaps (eglSwapBuffers, a page
// flip) behind it; the files output has nothing to swap, so its present is the moment it runs.
#include <cstdint>
#include <functional>

#include "util/monotonic_clock.hpp"

namespace cupola {

using FramePresenter = std::function<uint64_t(uint64_t frame)>;

// The files output: the frame is already on its way to disk; "shown" now.
inline FramePresenter files_presenter() {
    return [](uint64_t) { return monotonic_ns(); };
}

}  // namespace cupola
