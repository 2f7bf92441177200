#pragma once
// The sky behind the stars in one frame: what the star pass needs to judge, star by star, whether
// the eye could see it against the sky (shaders/shared/star_visibility.glsl). Everything here
// comes from world positions in double, the same on every channel.
#include <glm/glm.hpp>

#include "atmosphere/solar_scale.hpp"
#include "passes/frame_context.hpp"
#include "shading/shared_types.hpp"

namespace cupola {

class GpuSkyViewTable;

struct StarSky {
    GpuSkyViewTable* table = nullptr;  // null: no sky to judge by (the exposure alone decides)
    glm::vec2 table_in{0.0f};          // the table's (camera distance, Sun zenith cosine): GpuSkyViewTable::update
    shading::AtmosphereParams params{};
    glm::vec3 center_dir_world{0.0f, 0.0f, -1.0f};  // unit, camera -> planet centre
    glm::vec3 sun_world{0.0f, 0.0f, 1.0f};          // unit, planet centre -> Sun
    float to_cd_m2 = 0.0f;                          // the table's values (per unit solar irradiance) to cd/m^2
    float night_sky_cd_m2 = 0.0f;  // the night sky's own glow at the zenith over the camera (shared/night_sky.glsl)
    // The moonlit sky (common/atmosphere/moonlit_sky.hpp): the Moon's table (null when its light is off), its
    // zenith cosine on the tables' grid, its direction (unit, camera -> Moon) and its luminous
    // irradiance over the Sun's.
    GpuSkyViewTable* moon_table = nullptr;
    float moon_mu = 0.0f;
    glm::vec3 moon_world{0.0f, 0.0f, 1.0f};
    float moon_ratio = 0.0f;
};

// Who knows the sky: the atmosphere pass (AtmospherePass::star_sky).
class StarSkySource {
public:
    virtual ~StarSkySource() = default;
    virtual StarSky star_sky(const FrameContext& frame) const = 0;
};

}  // namespace cupola
