// The relief's shadows on the CPU (common/terrain/tile_horizon, shaders/shared/terrain_light.glsl
// compiled as C++): the packed horizon round-trips, the visibility turns on the Sun's elevation
// against the horizon in its azimuth, and a tile's horizon map shadows a cone's lee at a low Sun as a
// ray march along the Sun's exact azimuth over the finest relief does.
#include <gtest/gtest.h>

#include <cmath>

#include "config/scene_config.hpp"
#include "shading/shared_shading.hpp"
#include "support/earth_moon_scene.hpp"
#include "support/geotiff_writer.hpp"
#include "support/test_support.hpp"
#include "terrain/body_relief.hpp"
#include "terrain/cube_sphere.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_horizon.hpp"
#include "terrain/tile_key.hpp"
#include "terrain/tile_mesh.hpp"

using namespace cupola;
namespace sh = cupola::shading;

namespace {

constexpr double kDeg = 0.017453292519943295769;

// The local east, north at a point (the horizon map's frame).
struct Frame {
    glm::dvec3 east, north;
};
Frame frame_at(const glm::dvec3& up) {
    const glm::dvec3 e = glm::normalize(glm::dvec3(sh::terrain_east(glm::vec3(up))));
    return {e, glm::cross(up, e)};
}

// The Sun at azimuth az (from east toward north) and elevation el seen from `up`.
glm::dvec3 sun_at(const glm::dvec3& up, double az_rad, double el_rad) {
    const Frame f = frame_at(up);
    return glm::normalize(std::cos(el_rad) * (std::cos(az_rad) * f.east + std::sin(az_rad) * f.north) +
                          std::sin(el_rad) * up);
}

// The true horizon's sine toward a (body-frame) tangent direction t: the finest relief every
// step_m along the great circle up to reach_m.
double marched_horizon(const terrain::Relief& relief, const glm::dvec3& d, double h0, const glm::dvec3& t,
                       double step_m, double reach_m) {
    const double r = relief.radius_m();
    double best = -1.0;
    for (double s = step_m; s <= reach_m; s += step_m) {
        const glm::dvec3 q = d * std::cos(s / r) + t * std::sin(s / r);
        const glm::dvec3 p = q * (r + relief.height_m(q, 0.0)) - d * (r + h0);
        best = std::max(best, glm::dot(p, d) / glm::length(p));
    }
    return best;
}

// The Earth with a cone 2000 m high, 0.5 degrees in radius, at 45.5 N 10.25 E (a GeoTIFF the test
// writes) and no procedural relief.
terrain::BodyRelief cone_relief(const std::string& tag) {
    const std::string dir = test::scratch_dir(tag);
    const auto cone = [](double lon, double lat) {
        return std::max(0.0, 2000.0 * (1.0 - std::hypot(lon - 10.25, lat - 45.5) / 0.5));
    };
    SceneConfig sc = test::earth_moon_scene();
    BodyConfig& earth = sc.bodies[sc.find("earth")->id];
    earth.terrain.present = true;
    earth.terrain.procedural_amplitude_m = 0.0;  // the cone alone
    earth.terrain.elevation = test::write_geotiff(dir + "/cone.tif", 150, 100, 9.5, 46.0, 0.01, cone);
    terrain::BodyRelief opened = terrain::open_body_relief(earth);
    EXPECT_TRUE(opened.fallback.empty()) << opened.fallback;
    return opened;
}

}  // namespace

TEST(TerrainHorizon, PackingKeepsEverySineToAQuarterOfAMilli) {
    terrain::HorizonSines s = {-1.0, -0.3, 0.0, 0.01, 0.2, 0.5, 0.999, 1.0};
    const glm::vec4 packed = terrain::pack_horizon(s);
    for (int k = 0; k < terrain::kHorizonDirections; ++k)
        EXPECT_NEAR(sh::terrain_horizon_sine(packed, k), s[k], 0.5 / 4095.0 * 2.0 + 1e-7) << k;
    // Zeros (a mesh without a horizon map) are a horizon at -90 degrees: in the open.
    EXPECT_EQ(sh::terrain_sun_visibility(glm::vec4(0.0f), glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 0, 0.01f))),
              1.0f);
}

// The Sun is seen above the horizon in its own azimuth, interpolated between the eight.
TEST(TerrainHorizon, TheSunIsSeenAboveTheHorizonInItsAzimuth) {
    const glm::dvec3 up = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    terrain::HorizonSines s;
    for (int k = 0; k < terrain::kHorizonDirections; ++k) s[k] = std::sin((1.0 + k) * kDeg);  // 1..8 degrees
    const glm::vec4 packed = terrain::pack_horizon(s);
    for (double az_deg : {0.0, 30.0, 100.0, 200.0, 300.0, 350.0}) {
        // The horizon in this azimuth, between its two neighbours (350: between 8 and 1 degrees).
        const double f = az_deg / 45.0;
        const int k0 = static_cast<int>(f) % 8, k1 = (k0 + 1) % 8;
        const double horizon_deg = glm::degrees(std::asin(s[k0] + (f - std::floor(f)) * (s[k1] - s[k0])));
        const auto seen = [&](double el_deg) {
            return sh::terrain_sun_visibility(packed, glm::vec3(up),
                                              glm::vec3(sun_at(up, az_deg * kDeg, el_deg * kDeg)));
        };
        EXPECT_EQ(seen(horizon_deg + 1.5), 1.0f) << az_deg;
        EXPECT_EQ(seen(horizon_deg - 1.5), 0.0f) << az_deg;
        EXPECT_NEAR(seen(horizon_deg), 0.5f, 0.1f) << az_deg;
    }
}

// A cone 2000 m high, 0.5 degrees across, the Sun 1.5 degrees high in the east: a tile 40 km
// across west of it lies partly in its shadow. Its horizon map agrees with a ray march toward the
// Sun's exact azimuth over the finest relief, except within the shadow's soft edge.
TEST(TerrainHorizon, ATilesHorizonMapShadowsAConesLeeAsARayMarchDoes) {
    const terrain::BodyRelief opened = cone_relief("terrain_horizon_cone");
    const terrain::Relief& relief = *opened.relief;
    const glm::dvec3 lee = terrain::lat_lon_to_direction(test::centric_deg(45.5) * kDeg, (10.25 - 0.65) * kDeg);
    const terrain::TileMesh mesh = terrain::build_tile_mesh(terrain::tile_at(lee, 8), relief, 32, true);
    ASSERT_EQ(mesh.horizon.size(), mesh.directions.size());
    // One Sun for the whole tile (as the GPU has it): east of the lee point, 1.5 degrees up there.
    const glm::dvec3 sun = sun_at(lee, 0.0, 1.5 * kDeg);
    const double reach = terrain::horizon_reach_m(relief);
    int shadowed = 0, lit = 0, wrong = 0, on_edge = 0;
    for (size_t k = 0; k < mesh.directions.size(); ++k) {
        const glm::dvec3 d = mesh.directions[k];
        const double sun_sine = glm::dot(sun, d);
        const glm::dvec3 toward = glm::normalize(sun - d * sun_sine);  // the Sun's azimuth at this vertex
        const double truth = marched_horizon(relief, d, mesh.height_m[k], toward, 250.0, reach);
        const float seen = sh::terrain_sun_visibility(mesh.horizon[k], glm::vec3(d), glm::vec3(sun));
        if (std::abs(sun_sine - truth) < 0.002) {  // within a ninth of a degree: either answer
            ++on_edge;
            continue;
        }
        const bool truly_lit = sun_sine > truth;
        (truly_lit ? lit : shadowed) += 1;
        if ((seen > 0.5f) != truly_lit) ++wrong;
    }
    const int counted = lit + shadowed;
    std::printf("horizon map: %d lit, %d shadowed, %d wrong, %d on the edge\n", lit, shadowed, wrong, on_edge);
    EXPECT_GT(shadowed, counted / 10) << "the tile must lie partly in the cone's shadow";
    EXPECT_GT(lit, counted / 10) << "and partly in the light";
    EXPECT_LE(wrong, counted * 3 / 100) << wrong << " of " << counted << " vertices (" << on_edge << " on the edge)";
}

// A tile 2.4 km across, 0.9 degrees (70 km) west of the cone's top: the cone lies past 16 tile
// widths, among the samples the tile takes once for all its points. At every point where the map is computed (every
// fourth vertex) it agrees in every azimuth with the point's own samples of the relief (horizon_sines) within 0.002 in
// sine, a fifth of the shadow's soft edge; and toward the cone the horizon stands above 1 degree.
TEST(TerrainHorizon, TheTilesSharedFarSamplesGiveEveryPointItsOwnHorizon) {
    const terrain::BodyRelief opened = cone_relief("terrain_horizon_far");
    const terrain::Relief& relief = *opened.relief;
    const glm::dvec3 west = terrain::lat_lon_to_direction(test::centric_deg(45.5) * kDeg, (10.25 - 0.9) * kDeg);
    const int level = 12, segments = 32;
    const terrain::TileMesh mesh = terrain::build_tile_mesh(terrain::tile_at(west, level), relief, segments, true);
    const double spacing = terrain::tile_spacing_m(level, segments, mesh.radius_m);
    ASSERT_LT(16.0 * segments * spacing, 40e3) << "the cone's top must lie among the shared samples";
    const double reach = std::max(terrain::horizon_reach_m(relief), 4.0 * spacing);
    double worst = 0.0, toward_cone = -1.0;
    for (int j = 0; j <= segments; j += segments / 8)
        for (int i = 0; i <= segments; i += segments / 8) {
            const size_t k = mesh.index(i, j);
            const terrain::HorizonSines own =
                terrain::horizon_sines(relief, mesh.directions[k], mesh.height_m[k], spacing, reach);
            for (int a = 0; a < terrain::kHorizonDirections; ++a)
                worst = std::max(worst, std::abs(sh::terrain_horizon_sine(mesh.horizon[k], a) - own[a]));
            toward_cone = std::max(toward_cone, own[0]);  // azimuth 0: east
        }
    std::printf("shared far samples: worst sine difference %.5f; horizon toward the cone up to %.2f degrees\n", worst,
                glm::degrees(std::asin(toward_cone)));
    EXPECT_GT(toward_cone, std::sin(1.0 * kDeg));
    EXPECT_LT(worst, 0.002);
}
