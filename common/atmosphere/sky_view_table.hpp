#pragma once
// The sky-view table on the CPU (shaders/shared/atmosphere_sky_view.glsl): the same texels the
// GPU computes each frame, built by the shared code for one camera distance and Sun zenith
// cosine. The production model looks its validation queries up in it (production_model.cpp), so
// the error measured on the CPU is that of the table the GPU draws with.
#include <array>

#include "shading/shared_shading.hpp"

namespace cupola::atmosphere {

class ProductionAtmosphere;

struct SkyViewTable {
    float d_m = 0.0f;                             // camera to planet centre
    float mu_s = 0.0f;                            // Sun zenith cosine at the camera
    std::array<shading::Texture2DData, 3> parts;  // the texel parts 0..2 of the header, RGBA32F

    glm::vec2 size() const { return glm::vec2(parts[0].width, parts[0].height); }
};

// The Sun's zenith cosine a table is built for: the zenith angle (from the double mu_s every
// channel derives from the snapshot alike) rounded to the nearest multiple of
// kSkyViewSunStep_deg. With time running at the real rate the Sun moves 0.0042 degrees a second,
// so the table is re-rendered about every 0.24 s (every 14th frame at 60 Hz) instead of every
// frame, on every channel at the same frame; the pixel still takes the Sun's true direction (the
// Mie phase, the azimuth). Half a step costs at most 0.14 % (p99 of the texels) at sunset
// (test_atmosphere_sky_view); 0.01 degrees would cost 9 %.
inline constexpr double kSkyViewSunStep_deg = 0.001;
float sky_view_table_sun_mu(double mu_s);

// Builds the table of `model`'s quality (sky_view_width x sky_view_height, sky_view_samples steps).
SkyViewTable build_sky_view_table(const ProductionAtmosphere& model, float d_m, float mu_s);

}  // namespace cupola::atmosphere
