#pragma once
// Easing curves for show segments: how a keyframed value moves from one key to the next.
// Each maps the segment's linear progress f in [0, 1] to [0, 1] with e(0) = 0 and e(1) = 1.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace cupola {

enum class Easing {
    Linear,     // constant speed (the default for simulation time: a steady clock rate)
    EaseIn,     // starts at rest, arrives at speed
    EaseOut,    // leaves at speed, arrives at rest
    EaseInOut,  // starts and arrives at rest (smoothstep; the default for the camera)
    Hold,       // stays at the first key until the next key's time, then jumps
};

inline const std::vector<std::string>& easing_names() {
    static const std::vector<std::string> names = {"linear", "ease_in", "ease_out", "ease_in_out", "hold"};
    return names;
}

inline Easing easing_from_name(const std::string& name) {
    const auto& n = easing_names();
    const auto it = std::find(n.begin(), n.end(), name);
    if (it == n.end()) throw std::invalid_argument("unknown easing \"" + name + "\"");
    return static_cast<Easing>(it - n.begin());
}

inline double ease(Easing e, double f) {
    f = std::clamp(f, 0.0, 1.0);
    switch (e) {
        case Easing::Linear:
            return f;
        case Easing::EaseIn:
            return f * f;
        case Easing::EaseOut:
            return f * (2.0 - f);
        case Easing::EaseInOut:
            return f * f * (3.0 - 2.0 * f);
        case Easing::Hold:
            return f < 1.0 ? 0.0 : 1.0;
    }
    return f;
}

}  // namespace cupola
