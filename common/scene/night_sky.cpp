#include "scene/night_sky.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "shading/shared_shading.hpp"

namespace cupola {

double bortle_zenith_mag_arcsec2(int bortle_class) {
    // Classes 1..9: 21.99-22.0, 21.89-21.99, 21.69-21.89, 20.49-21.69, 19.50-20.49, 18.94-19.50,
    // 18.38-18.94, and below 18.38 for 8 and 9 (8 taken at 18.0, 9 at 17.5).
    static constexpr std::array<double, 9> kMid = {22.0, 21.94, 21.79, 21.09, 20.0, 19.22, 18.66, 18.0, 17.5};
    if (bortle_class < 1 || bortle_class > 9)
        throw std::invalid_argument("Bortle class " + std::to_string(bortle_class) + " is not 1 .. 9");
    return kMid[static_cast<size_t>(bortle_class - 1)];
}

double sky_brightness_cd_m2(double mag_arcsec2) {
    return shading::night_sky_cd_m2_of_mag(static_cast<float>(mag_arcsec2));
}

}  // namespace cupola
