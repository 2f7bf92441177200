#include "navigation/input_shaper.hpp"

#include <algorithm>
#include <cmath>

namespace cupola {

namespace {

// Below this a smoothed axis is exactly 0 (the exponential tail would otherwise never end).
constexpr double kSnapToZero = 1e-9;

// Dead zone and response curve of one axis: 0 inside the dead zone, then
// sign(x) * ((|x| - dz) / (1 - dz))^exponent, which is 0 at the edge and 1 at full deflection.
double curve(double x, const ShaperTuning& t) {
    if (!std::isfinite(x)) return 0.0;
    x = std::clamp(x, -1.0, 1.0);
    const double a = std::abs(x);
    if (a <= t.dead_zone) return 0.0;
    const double r = std::pow((a - t.dead_zone) / (1.0 - t.dead_zone), t.exponent);
    return std::copysign(std::min(r, 1.0), x);
}

}  // namespace

InputShaper::InputShaper(ShaperTuning tuning) : tuning_(tuning) {
    // Keep the formulas defined whatever the configuration says.
    if (!std::isfinite(tuning_.dead_zone)) tuning_.dead_zone = 0.0;
    tuning_.dead_zone = std::clamp(tuning_.dead_zone, 0.0, 0.999);
    if (!std::isfinite(tuning_.smoothing_s) || tuning_.smoothing_s < 0.0) tuning_.smoothing_s = 0.0;
    if (!std::isfinite(tuning_.exponent) || tuning_.exponent <= 0.0) tuning_.exponent = 1.0;
}

void InputShaper::reset() { state_ = NavAxes{}; }

bool InputShaper::outside_dead_zone(const NavSample& s) const {
    if (!s.connected) return false;
    const NavAxes& a = s.axes;
    for (double x : {a.right, a.up, a.forward, a.pitch_up, a.yaw_left, a.roll_ccw})
        if (curve(x, tuning_) != 0.0) return true;
    return false;
}

NavAxes InputShaper::shape(const NavSample& s, double dt_s) {
    if (!s.connected) {
        reset();
        return NavAxes{};
    }
    // Fraction of the way to the new value this frame: 1 - exp(-dt/tau) composes exactly, so n
    // frames of dt/n end where one frame of dt does (frame-rate independent).
    double alpha = 1.0;
    if (tuning_.smoothing_s > 0.0) {
        const bool valid_dt = std::isfinite(dt_s) && dt_s > 0.0;
        alpha = valid_dt ? 1.0 - std::exp(-dt_s / tuning_.smoothing_s) : 0.0;
    }
    auto follow = [&](double& state, double raw) {
        const double target = curve(raw, tuning_);
        state = alpha >= 1.0 ? target : state + alpha * (target - state);
        if (std::abs(state) < kSnapToZero) state = 0.0;
    };
    follow(state_.right, s.axes.right);
    follow(state_.up, s.axes.up);
    follow(state_.forward, s.axes.forward);
    follow(state_.pitch_up, s.axes.pitch_up);
    follow(state_.yaw_left, s.axes.yaw_left);
    follow(state_.roll_ccw, s.axes.roll_ccw);
    return state_;
}

}  // namespace cupola
