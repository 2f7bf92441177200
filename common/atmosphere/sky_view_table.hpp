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

// Builds the table of `model`'s quality (sky_view_width x sky_view_height, sky_view_samples steps).
SkyViewTable build_sky_view_table(const ProductionAtmosphere& model, float d_m, float mu_s);

}  // namespace cupola::atmosphere
