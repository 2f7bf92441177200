// End to end: the calibrated 4-projector dome (configs/dome-4proj.json, made by cupola-mpcdi-gen)
// through real processes: a master and four slaves whose output stage warps and blends each
// channel render into its projector raster on the GPU pass, written by the files sink. A white
// field (the alignment pattern) must then light the dome evenly:
//  - physically: the projector frames' light, where the ideal projectors of the generator throw it
//    onto the dome (common/calibration/projector_stitch), summed, is flat within 2 %;
//  - through the calibration: cupola-loopback's own domemaster of the projector frames
//    (common/dome/projector_frame_stitcher) is flat too.
// And a channel can feed a Paul Bourke mesh (a spherical mirror) instead of an MPCDI region.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "calibration/channel_warp.hpp"
#include "calibration/ideal_dome.hpp"
#include "calibration/reference_warp.hpp"
#include "config/config_error.hpp"
#include "calibration/projector_stitch.hpp"
#include "image/frame_image.hpp"
#include "projection/fisheye.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"

using namespace cupola;
namespace fs = std::filesystem;

namespace {

// configs/dome-4proj.json with the repository's paths made absolute, small channel renders and a
// show that turns on one alignment pattern from the start.
nlohmann::json calibrated_cluster(const std::string& dir, const std::string& pattern, int port) {
    nlohmann::json c = nlohmann::json::parse(test::read_text(test::source_path("configs/dome-4proj.json")));
    c["scene"] = test::source_path("configs/scenes/earth-moon.json");
    nlohmann::json show = nlohmann::json::parse(test::read_text(test::source_path("configs/shows/alignment.json")));
    show["events"] = nlohmann::json::array({{{"at_s", 0}, {"pattern", pattern}}});
    test::write_text(dir + "/show.json", show.dump(2));
    c["show"] = dir + "/show.json";
    c["network"]["snapshot_port"] = port;
    c["network"]["report_port"] = port + 1;
    c["output"]["width"] = 160;
    c["output"]["height"] = 160;
    c["output"]["domemaster_size"] = 256;
    for (auto& ch : c["channels"])
        ch["calibration"]["mpcdi"] = test::source_path("configs/" + ch["calibration"]["mpcdi"].get<std::string>());
    return c;
}

// The projector frame's 8-bit values as they go to the projector (no decoding), in [0,1].
Image read_encoded_frame(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error(path + ": " + OIIO::geterror());
    const auto& spec = in->spec();
    Image im;
    im.width = spec.width, im.height = spec.height;
    std::vector<float> px(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data());
    im.rgba.assign(static_cast<size_t>(im.width) * im.height * 4, 1.0f);
    for (size_t i = 0; i < static_cast<size_t>(im.width) * im.height; ++i)
        for (int k = 0; k < 3; ++k) im.rgba[i * 4 + k] = px[i * spec.nchannels + std::min(k, spec.nchannels - 1)];
    return im;
}

struct Flatness {
    double min = 1e30, max = -1e30;
    long samples = 0;
};

// Luminance over the domemaster pixels above `min_elevation_deg` (the springline's own pixels are
// half on the screen).
Flatness flatness(const Image& dome, double min_elevation_deg) {
    Flatness f;
    const FisheyeMapping fisheye(180.0);
    for (int y = 0; y < dome.height; ++y)
        for (int x = 0; x < dome.width; ++x) {
            const auto dir = fisheye.uv_to_direction(FisheyeMapping::pixel_to_uv({x + 0.5, y + 0.5}, dome.width));
            if (!dir || glm::degrees(std::asin(dir->y)) < min_elevation_deg) continue;
            const float* p = dome.pixel(x, y);
            const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            f.min = std::min(f.min, l), f.max = std::max(f.max, l);
            ++f.samples;
        }
    return f;
}

}  // namespace

TEST(CalibratedDome, WhiteFieldThroughFourWarpedBlendedProjectorsLightsTheDomeEvenly) {
    const std::string dir = test::scratch_dir("calibrated_dome_white");
    const std::string out = test::run_loopback(dir, calibrated_cluster(dir, "white", 47940), 2);

    std::vector<Image> frames;
    std::vector<double> gammas;
    for (const char* name : {"proj0", "proj1", "proj2", "proj3"}) {
        frames.push_back(read_encoded_frame(out + "/" + name + "/" + frame_file_name(1, "png")));
        ASSERT_EQ(frames.back().width, 640) << name << ": the projector raster comes from the calibration";
        ASSERT_EQ(frames.back().height, 400);
        ASSERT_TRUE(fs::exists(out + "/" + name + "/" + frame_file_name(1, "exr")));
        gammas.push_back(2.2);
    }
    // Where the generator's ideal projectors throw the light (its defaults made the committed file).
    const auto projectors = make_projectors(IdealDome{}, projector_ring(ProjectorRing{}));
    const Flatness physical = flatness(stitch_projector_frames(projectors, frames, gammas, 256), 2.0);
    ASSERT_GT(physical.samples, 40000);
    EXPECT_GT(physical.min, 0.98) << "the dome is darker somewhere, e.g. in an overlap";
    EXPECT_LT(physical.max, 1.02) << "the dome is brighter somewhere, e.g. in an overlap";

    // The same frames put back through the calibration by the loopback (summed, not feathered).
    const Image dome = read_image_radiance(out + "/dome/" + frame_file_name(1, "exr"));
    const Flatness stitched = flatness(dome, 2.0);
    EXPECT_GT(stitched.min, 0.97);
    EXPECT_LT(stitched.max, 1.03);
    std::printf("white field on the dome: physical %.4f..%.4f, through the calibration %.4f..%.4f\n", physical.min,
                physical.max, stitched.min, stitched.max);
}

namespace {

// A 5x5 Bourke mesh over a 16:10 screen showing the middle of the channel render.
std::string small_bourke_mesh() {
    std::ostringstream s;
    s << "2\n5 5\n";
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const double x = 1.6 * (-1.0 + 0.5 * i), y = 1.0 - 0.5 * j;
            s << x << " " << y << " " << 0.25 + 0.5 * i / 4.0 << " " << 0.25 + 0.5 * (4 - j) / 4.0 << " 1\n";
        }
    return s.str();
}

// dome-4ch.json whose first channel feeds a spherical-mirror projector through `calibration`.
std::string bourke_cluster(const std::string& dir, const nlohmann::json& calibration) {
    nlohmann::json c = nlohmann::json::parse(test::read_text(test::write_test_cluster(dir, 47950, 64, 64)));
    c["channels"][0]["calibration"] = calibration;
    test::write_text(dir + "/bourke.json", c.dump(2));
    return dir + "/bourke.json";
}

void expect_config_error(const std::string& file, const std::string& field) {
    try {
        load_cluster_config(file);
        ADD_FAILURE() << "no error naming " << field;
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

}  // namespace

TEST(CalibratedDome, ChannelFeedsABourkeMeshAtTheConfiguredRasterAndBadReferencesAreNamed) {
    const std::string dir = test::scratch_dir("calibrated_bourke");
    test::write_text(dir + "/mirror.data", small_bourke_mesh());
    const auto cfg = load_cluster_config(
        bourke_cluster(dir, {{"bourke", "mirror.data"}, {"raster_width", 80}, {"raster_height", 50}}));
    const ChannelConfig& ch = cfg.channels[0];
    ASSERT_TRUE(ch.calibration);
    EXPECT_FALSE(ch.calibration->frustum_from_file);
    const ProjectorWarp warp = load_channel_warp(*ch.calibration);
    EXPECT_EQ(warp.raster_width, 80);
    EXPECT_EQ(warp.raster_height, 50);
    // The screen's centre shows the render's centre (the mesh maps the middle half of it).
    const glm::dvec2 uv = warp_uv_at(warp, 40.0, 25.0);
    EXPECT_NEAR(uv.x, 0.5, 1e-6);
    EXPECT_NEAR(uv.y, 0.5, 1e-6);

    expect_config_error(bourke_cluster(dir, {{"bourke", "mirror.data"}, {"raster_height", 50}}), "raster_width");
    expect_config_error(bourke_cluster(dir, {{"bourke", "absent.data"}, {"raster_width", 8}, {"raster_height", 5}}),
                        "calibration.bourke");
    test::write_text(dir + "/broken.data", "2\n5 5\n0 0 0.5 0.5 1\n");
    expect_config_error(bourke_cluster(dir, {{"bourke", "broken.data"}, {"raster_width", 8}, {"raster_height", 5}}),
                        "broken.data");
}
