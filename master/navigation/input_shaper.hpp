#pragma once
// Turns raw device axes into what the navigation model should act on: a dead zone per axis (a
// device at rest reads slightly off zero), a response curve (fine control near rest) and
// frame-rate independent exponential smoothing (no jerks from a noisy or coarse device).
//
// Guarantees the navigation model relies on:
//   - a device at rest (every axis inside the dead zone) gives exactly 0, so the camera does not
//     drift; values that smooth away below 1e-9 snap to exactly 0;
//   - a sample with connected == false gives exactly 0 at once and forgets the smoothing state:
//     unplugging stops the camera in the next frame, with no smoothing tail.
#include "input/nav_input.hpp"

namespace cupola {

struct ShaperTuning {
    double dead_zone = 0.08;    // |x| up to this reads as 0; beyond, rescaled so 0 -> 1 is continuous
    double smoothing_s = 0.12;  // time constant of the exponential smoothing (0: none)
    double exponent = 2.0;      // response curve |x|^exponent after the dead zone (1: linear)
};

class InputShaper {
public:
    explicit InputShaper(ShaperTuning tuning = {});

    // The shaped axes for a sample taken dt_s seconds after the previous one. Each axis is
    // clamped to -1..1 first; a non-finite axis reads as 0. dt_s <= 0 (or non-finite) keeps the
    // smoothed state where it is.
    NavAxes shape(const NavSample& s, double dt_s);
    // Whether the device is held outside its dead zone now (one axis is enough), whatever the
    // smoothing still carries.
    bool outside_dead_zone(const NavSample& s) const;

    // Forget the smoothing state (the next output starts from rest).
    void reset();

    const ShaperTuning& tuning() const { return tuning_; }

private:
    ShaperTuning tuning_;
    NavAxes state_;  // smoothed output so far
};

}  // namespace cupola
