// The ideal-dome calibration (common/calibration/ideal_dome*.hpp, tools/mpcdi_gen): the projector
// model's inverse, the warp geometry against the analytic rays, the MPCDI round trip, the blend's
// flatness on the dome (and the naive output's failure), for fisheye and normal lenses, and the
// committed demo package (configs/calibration/dome-4proj.mpcdi) against a fresh generation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <tuple>

#include "calibration/ideal_dome_checks.hpp"
#include "calibration/ideal_dome_package.hpp"
#include "calibration/ideal_dome_warp.hpp"
#include "calibration/mpcdi_package.hpp"
#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

// The demo: the generator's defaults (configs/dome-4proj.json).
IdealCalibrationSpec fisheye_spec() {
    IdealCalibrationSpec spec;
    spec.projectors = projector_ring(ProjectorRing{});
    return spec;
}

// Four normal (pinhole) lenses, 80 degrees across, at a small raster; 1.25-pixel grid cells: the
// lens lights the raster's edges, whose outer half cells the reader clamps (reference_warp.hpp).
IdealCalibrationSpec normal_spec() {
    ProjectorRing ring;
    ring.lens = {LensKind::Normal, 80.0, 0.0};
    ring.distance_fraction = 0.9;
    ring.pitch_deg = 25.0;
    ring.raster_width = 160;
    ring.raster_height = 100;
    IdealCalibrationSpec spec;
    spec.projectors = projector_ring(ring);
    spec.grid_columns = 128;
    spec.grid_rows = 80;
    spec.ramp.width_px = 16.0;
    spec.alpha_width = 160;  // at this coarse raster, a half-size alpha map steps the ramp by 3 %
    spec.alpha_height = 100;
    return spec;
}

std::vector<ProjectorWarp> write_and_read(const std::vector<ProjectorWarp>& warps, const std::string& file) {
    write_ideal_dome_mpcdi(file, warps);
    const auto package = MpcdiPackage::open(file);
    EXPECT_EQ(package.profile(), "3d");
    EXPECT_EQ(package.regions().size(), warps.size());
    std::vector<ProjectorWarp> back;
    for (const auto& w : warps) back.push_back(package.read_region(w.region_id));
    return back;
}

// The largest difference between two warps' grids, frustum angles and alpha maps; NaN points must
// be NaN in both (counted in nan_mismatch).
struct WarpDifference {
    double uv = 0.0, frustum_deg = 0.0, alpha = 0.0;
    size_t nan_mismatch = 0;
};
WarpDifference difference(const ProjectorWarp& a, const ProjectorWarp& b) {
    WarpDifference d;
    EXPECT_EQ(a.raster_width, b.raster_width);
    EXPECT_EQ(a.raster_height, b.raster_height);
    EXPECT_EQ(a.grid.columns, b.grid.columns);
    EXPECT_EQ(a.grid.rows, b.grid.rows);
    if (a.grid.uv.size() != b.grid.uv.size() || a.alpha.value.size() != b.alpha.value.size() || !a.frustum ||
        !b.frustum)
        return {1e9, 1e9, 1e9, 1};
    for (size_t k = 0; k < a.grid.uv.size(); ++k) {
        const bool na = std::isnan(a.grid.uv[k].x), nb = std::isnan(b.grid.uv[k].x);
        if (na != nb) ++d.nan_mismatch;
        if (!na && !nb) d.uv = std::max(d.uv, glm::length(a.grid.uv[k] - b.grid.uv[k]));
    }
    const CalibratedFrustum &fa = *a.frustum, &fb = *b.frustum;
    for (double v :
         {fa.orientation.yaw_deg - fb.orientation.yaw_deg, fa.orientation.pitch_deg - fb.orientation.pitch_deg,
          fa.orientation.roll_deg - fb.orientation.roll_deg, fa.fov.left_deg - fb.fov.left_deg,
          fa.fov.right_deg - fb.fov.right_deg, fa.fov.up_deg - fb.fov.up_deg, fa.fov.down_deg - fb.fov.down_deg})
        d.frustum_deg = std::max(d.frustum_deg, std::abs(v));
    for (size_t k = 0; k < a.alpha.value.size(); ++k)
        d.alpha = std::max(d.alpha, static_cast<double>(std::abs(a.alpha.value[k] - b.alpha.value[k])));
    return d;
}

void expect_geometry_within_bounds(const IdealCalibrationSpec& spec, const std::vector<ProjectorWarp>& warps,
                                   const char* what) {
    const auto projectors = make_projectors(spec.dome, spec.projectors);
    const WarpGeometryError e = measure_warp_geometry(projectors, warps);
    std::printf("%s warp geometry: %zu pixels, %zu not shown, median %.4f px, p99 %.4f px, max %.3f px\n", what,
                e.pixels, e.not_shown, e.median_px, e.p99_px, e.max_px);
    EXPECT_GT(e.pixels, 0u);
    EXPECT_EQ(e.not_shown, 0u) << "projector pixels on the dome that the warp shows as black";
    EXPECT_LE(e.p99_px, 0.5);
    EXPECT_LE(e.median_px, 0.1);
}

void expect_blend_flat(const IdealCalibrationSpec& spec, const std::vector<ProjectorWarp>& warps, const char* what) {
    const auto projectors = make_projectors(spec.dome, spec.projectors);
    // Two degrees above the springline: the light of the pixels across it is spread by the
    // bilinear reconstruction of projector_stitch over up to one (coarse, in the normal rig) pixel.
    const BlendFlatness b = measure_blend_flatness(projectors, warps, {}, 192, 2.0);
    std::printf(
        "%s blend: %zu samples, %zu in overlaps, light %.4f .. %.4f, max deviation %.2f %% (overlaps %.2f %%)\n", what,
        b.samples, b.overlap_samples, b.min_light, b.max_light, 100.0 * b.max_deviation,
        100.0 * b.max_overlap_deviation);
    EXPECT_EQ(b.dark_samples, 0u) << "the projectors leave a hole in the dome";
    EXPECT_GT(b.overlap_samples, b.samples / 10) << "the rig should overlap";
    EXPECT_LE(b.max_deviation, 0.02);
    ProjectorFrameOptions naive;
    naive.blend = false;
    const BlendFlatness n = measure_blend_flatness(projectors, warps, naive, 192, 2.0);
    std::printf("%s naive: light %.4f .. %.4f\n", what, n.min_light, n.max_light);
    EXPECT_GT(n.max_deviation, 0.02) << "without the blend the overlaps must be too bright";
    EXPECT_GE(n.max_light, 1.9);
}

}  // namespace

TEST(IdealDome, ProjectorModelInvertsForBothLenses) {
    for (const auto& spec : {fisheye_spec(), normal_spec()}) {
        const auto projectors = make_projectors(spec.dome, spec.projectors);
        for (const auto& p : projectors) {
            int checked = 0;
            for (int y = 0; y < p.height(); y += 7)
                for (int x = 0; x < p.width(); x += 7) {
                    const glm::dvec2 px(x + 0.5, y + 0.5);
                    if (!p.lights_screen(px)) continue;
                    const auto dir = p.pixel_dome_direction(px);
                    ASSERT_TRUE(dir);
                    EXPECT_NEAR(glm::length(*dir), 1.0, 1e-12);
                    const auto back = p.dome_direction_to_pixel(*dir);
                    ASSERT_TRUE(back);
                    EXPECT_LT(glm::length(*back - px), 1e-6) << p.placement().id << " at " << x << "," << y;
                    ++checked;
                }
            EXPECT_GT(checked, 50) << p.placement().id << " lights too little of the screen";
        }
    }
}

TEST(IdealDome, PlacementOutsideTheDomeIsRefusedByName) {
    IdealCalibrationSpec spec = fisheye_spec();
    spec.projectors[2].distance_fraction = 1.2;
    try {
        (void)ideal_projector_warps(spec);
        FAIL() << "a projector outside the dome was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("proj2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("distance_fraction"), std::string::npos) << e.what();
    }
}

TEST(IdealDome, MpcdiRoundTripKeepsTheWarp) {
    for (const auto& spec : {fisheye_spec(), normal_spec()}) {
        const auto warps = ideal_projector_warps(spec);
        const auto back = write_and_read(warps, test::scratch_dir("ideal_dome_round_trip") + "/dome.mpcdi");
        ASSERT_EQ(back.size(), warps.size());
        for (size_t k = 0; k < warps.size(); ++k) {
            const WarpDifference d = difference(warps[k], back[k]);
            EXPECT_EQ(back[k].region_id, warps[k].region_id);
            EXPECT_EQ(d.nan_mismatch, 0u);
            EXPECT_LE(d.uv, 1e-6) << warps[k].region_id;
            EXPECT_LE(d.frustum_deg, 1e-6) << warps[k].region_id;
            // 16-bit alpha stored with gammaEmbedded 2.2: one step is at most 2.2 / 65535 in linear.
            EXPECT_LE(d.alpha, 2.2 / 65535.0) << warps[k].region_id;
            EXPECT_NEAR(back[k].projector_gamma, warps[k].projector_gamma, 1e-9);
        }
    }
}

TEST(IdealDome, CommittedDemoPackageIsTheGeneratorsOutput) {
    const auto warps = ideal_projector_warps(fisheye_spec());
    const auto package = MpcdiPackage::open(test::source_path("configs/calibration/dome-4proj.mpcdi"));
    ASSERT_EQ(package.regions().size(), warps.size());
    for (const auto& w : warps) {
        const WarpDifference d = difference(w, package.read_region(w.region_id));
        EXPECT_EQ(d.nan_mismatch, 0u) << w.region_id << ": regenerate with cupola-mpcdi-gen (docs/MPCDI.md)";
        EXPECT_LE(d.uv, 1e-6) << w.region_id;
        EXPECT_LE(d.frustum_deg, 1e-6) << w.region_id;
    }
}

TEST(IdealDome, WarpGeometryFisheyeFromTheFile) {
    const auto spec = fisheye_spec();
    const auto back = write_and_read(ideal_projector_warps(spec), test::scratch_dir("ideal_dome_fisheye") + "/d.mpcdi");
    expect_geometry_within_bounds(spec, back, "fisheye");
}

TEST(IdealDome, WarpGeometryNormalLensFromTheFile) {
    const auto spec = normal_spec();
    const auto back = write_and_read(ideal_projector_warps(spec), test::scratch_dir("ideal_dome_normal") + "/d.mpcdi");
    expect_geometry_within_bounds(spec, back, "normal");
}

TEST(IdealDome, CoarseGridMissesTheGeometryBound) {
    // The check can fail: an 8 x 8 grid bends the straight projector rays by whole pixels.
    IdealCalibrationSpec spec = fisheye_spec();
    spec.grid_columns = spec.grid_rows = 8;
    const auto projectors = make_projectors(spec.dome, spec.projectors);
    EXPECT_GT(measure_warp_geometry(projectors, ideal_projector_warps(spec)).p99_px, 0.5);
}

TEST(IdealDome, BlendIsFlatOnTheDomeFisheye) {
    const auto spec = fisheye_spec();
    const auto back = write_and_read(ideal_projector_warps(spec), test::scratch_dir("ideal_dome_blend_f") + "/d.mpcdi");
    expect_blend_flat(spec, back, "fisheye");
}

TEST(IdealDome, BlendIsFlatOnTheDomeNormalLens) {
    const auto spec = normal_spec();
    const auto back = write_and_read(ideal_projector_warps(spec), test::scratch_dir("ideal_dome_blend_n") + "/d.mpcdi");
    expect_blend_flat(spec, back, "normal");
}

TEST(IdealDome, DemoConfigTakesItsChannelsFromThePackage) {
    const ClusterConfig config = load_cluster_config(test::source_path("configs/dome-4proj.json"));
    const auto warps = ideal_projector_warps(fisheye_spec());
    ASSERT_EQ(config.channels.size(), warps.size());
    for (size_t k = 0; k < warps.size(); ++k) {
        const ChannelConfig& c = config.channels[k];
        ASSERT_TRUE(c.calibration);
        EXPECT_EQ(c.calibration->region, warps[k].region_id);
        EXPECT_TRUE(c.calibration->frustum_from_file);
        EXPECT_EQ(c.calibration->raster_width, warps[k].raster_width);
        EXPECT_EQ(c.calibration->raster_height, warps[k].raster_height);
        EXPECT_NEAR(c.orientation.yaw_deg, warps[k].frustum->orientation.yaw_deg, 1e-6);
        EXPECT_NEAR(c.orientation.pitch_deg, warps[k].frustum->orientation.pitch_deg, 1e-6);
        EXPECT_NEAR(c.fov.left_deg, warps[k].frustum->fov.left_deg, 1e-6);
        EXPECT_NEAR(c.fov.up_deg, warps[k].frustum->fov.up_deg, 1e-6);
        EXPECT_NEAR(c.fov.down_deg, warps[k].frustum->fov.down_deg, 1e-6);
    }
}

TEST(IdealDome, ConfigNamesAMissingRegion) {
    const std::string dir = test::scratch_dir("ideal_dome_config");
    std::string text = test::read_text(test::source_path("configs/dome-4proj.json"));
    const std::string from = "\"region\": \"proj2\"";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), "\"region\": \"proj9\"");
    for (const char* rel : {"keys", "scenes", "shows", "calibration"})
        std::filesystem::create_directory_symlink(test::source_path(std::string("configs/") + rel), dir + "/" + rel);
    test::write_text(dir + "/bad.json", text);
    try {
        (void)load_cluster_config(dir + "/bad.json");
        FAIL() << "a missing region was accepted";
    } catch (const ConfigError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("channels[2].calibration.region"), std::string::npos) << what;
        EXPECT_NE(what.find("proj9"), std::string::npos) << what;
    }
    const std::string file = "calibration/dome-4proj.mpcdi";
    text.replace(text.find(file), file.size(), "calibration/none.mpcdi");
    test::write_text(dir + "/missing.json", text);
    try {
        (void)load_cluster_config(dir + "/missing.json");
        FAIL() << "a missing package was accepted";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("channels[0].calibration.mpcdi"), std::string::npos) << e.what();
    }
}

TEST(IdealDome, GeneratorChecksItsOwnFileAndStitchesFrames) {
    const std::string dir = test::scratch_dir("ideal_dome_generator");
    const std::string gen = test::bin_path("cupola-mpcdi-gen");
    const std::string small = " --raster-width 160 --raster-height 100";
    auto [rc, out] = test::run_shell(gen + " --out " + dir + "/d.mpcdi --images " + dir + " --check 2>&1");
    EXPECT_EQ(rc, 0) << out;
    EXPECT_NE(out.find("warp geometry"), std::string::npos) << out;
    // The stitch mode reads projector frames of the raster's size (here projector 0's, four times).
    const std::string f = dir + "/dome-4proj-frame.png";
    std::tie(rc, out) = test::run_shell(gen + " --out " + dir + "/d.mpcdi --stitch-frames " + f + " " + f + " " + f +
                                        " " + f + " --stitch-out " + dir + "/s.png 2>&1");
    EXPECT_EQ(rc, 0) << out;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/s.png")) << out;
    // A bound missed is a failing exit: an 8 x 8 grid.
    std::tie(rc, out) =
        test::run_shell(gen + " --out " + dir + "/c.mpcdi" + small + " --grid-columns 8 --grid-rows 8 --check 2>&1");
    EXPECT_EQ(rc, 1) << out;
    // Three frames for four projectors: an error naming the option.
    std::tie(rc, out) = test::run_shell(gen + " --out " + dir + "/d.mpcdi --stitch-frames " + f + " " + f + " " + f +
                                        " --stitch-out " + dir + "/t.png 2>&1");
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("--stitch-frames"), std::string::npos) << out;
}
