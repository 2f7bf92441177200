// Scene test: a real loopback run (master + slave processes, UDP, EGL, EXR files) flies
// from 400 km down to 1 km toward a sunset (configs/descent-1ch.json, auto exposure). The
// atmosphere must not jump where the camera enters it (60 km, exactly at show time 3 s): the
// frame-to-frame change there must be no larger than the largest change elsewhere in the flight.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "atmosphere/auto_exposure.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "director.hpp"
#include "master_node.hpp"
#include "show_script.hpp"
#include "image/frame_image.hpp"
#include "shading/shared_shading.hpp"
#include "support/cluster_fixture.hpp"
#include "support/loopback_run.hpp"
#include "util/child_process.hpp"

using namespace cupola;

namespace {
constexpr int kFrames = 29;      // show times 0 .. 7 s at 0.25 s per frame
constexpr int kEntryFrame = 12;  // show time 3 s: altitude 60 km, the top of the atmosphere

double mean_luminance(const Image& img) {
    double s = 0.0;
    for (int i = 0; i < img.width * img.height; ++i)
        s += 0.2126 * img.rgba[4 * i] + 0.7152 * img.rgba[4 * i + 1] + 0.0722 * img.rgba[4 * i + 2];
    return s / (img.width * img.height);
}

// Mean absolute luminance difference, relative to the pair's mean luminance.
double relative_change(const Image& a, const Image& b) {
    double d = 0.0;
    for (int i = 0; i < a.width * a.height; ++i) {
        const double la = 0.2126 * a.rgba[4 * i] + 0.7152 * a.rgba[4 * i + 1] + 0.0722 * a.rgba[4 * i + 2];
        const double lb = 0.2126 * b.rgba[4 * i] + 0.7152 * b.rgba[4 * i + 1] + 0.0722 * b.rgba[4 * i + 2];
        d += std::fabs(la - lb);
    }
    return d / (a.width * a.height) / (0.5 * (mean_luminance(a) + mean_luminance(b)));
}

// Runs the descent show through cupola-loopback at size x size; returns the output folder.
// With `side`, a second channel looks 100 degrees to the side of the first.
std::string run_descent(const std::string& name, int size, const std::vector<std::string>& formats, int port,
                        bool side = false) {
    const std::string dir = test::scratch_dir(name);
    setenv("CUPOLA_CACHE_DIR", (dir + "/cache").c_str(), 1);
    nlohmann::json c = nlohmann::json::parse(test::read_text(test::source_path("configs/descent-1ch.json")));
    for (const char* k : {"key_file", "scene", "show"}) c[k] = test::source_path("configs/" + c[k].get<std::string>());
    c["network"]["report_port"] = port + 1;
    c["channels"][0]["unicast_address"] = "127.0.0.1:" + std::to_string(port);
    c["network"]["channel_timeout_ms"] = 30000;
    c["network"]["hello_wait_ms"] = 60000;
    c["output"]["width"] = size;
    c["output"]["height"] = size;
    c["output"]["formats"] = formats;
    if (side) {
        nlohmann::json ch = c["channels"][0];
        ch["id"] = 1;
        ch["name"] = "side";
        ch["orientation"]["yaw_deg"] = 100;
        ch["unicast_address"] = "127.0.0.1:" + std::to_string(port + 2);
        c["channels"].push_back(ch);
    }
    const std::string config = dir + "/cluster.json";
    test::write_text(config, c.dump(2));
    const std::string out = dir + "/out";
    ChildProcess p({test::bin_path("cupola-loopback"), "--config", config, "--frames", std::to_string(kFrames), "--out",
                    out, "--timeout", "400", "--no-stitch"},
                   dir + "/loopback.log", {"DISPLAY", "WAYLAND_DISPLAY", "SPDLOG_LEVEL"});
    EXPECT_EQ(p.wait_for(std::chrono::seconds(420)).value_or(-1), 0) << test::read_text(dir + "/loopback.log");
    return out;
}
}  // namespace

TEST(AtmosphereDescent, NoDiscontinuityWhereTheCameraEntersTheAtmosphere) {
    const std::string out = run_descent("atmosphere_descent", 64, {"exr"}, 47880);
    ASSERT_FALSE(HasFailure());
    std::vector<Image> frames;
    std::vector<double> exposures;
    for (int f = 0; f < kFrames; ++f) {
        FrameMetadata meta;
        frames.push_back(read_image_radiance(out + "/sunset/" + frame_file_name(f, "exr"), &meta));
        for (float v : frames.back().rgba) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << "frame " << f;
        ASSERT_GT(mean_luminance(frames.back()), 0.0) << "frame " << f;
        exposures.push_back(meta.exposure);
    }
    std::vector<double> change(kFrames - 1);
    for (int f = 0; f + 1 < kFrames; ++f) change[f] = relative_change(frames[f], frames[f + 1]);
    double entry = 0.0, elsewhere = 0.0;
    for (int f = 0; f + 1 < kFrames; ++f) {
        const bool at_entry = f == kEntryFrame - 1 || f == kEntryFrame;
        (at_entry ? entry : elsewhere) = std::max(at_entry ? entry : elsewhere, change[f]);
        std::printf("frames %2d-%2d: change %.4f exposure %.3g%s\n", f, f + 1, change[f], exposures[f],
                    at_entry ? "  (entering the atmosphere)" : "");
    }
    EXPECT_LE(entry, elsewhere);
    // Auto exposure follows the scene: the exposure changed during the flight.
    EXPECT_NE(exposures.front(), exposures.back());
}

namespace {

struct DisplayedPart {
    int pixels = 0;
    int at_maximum = 0;       // a component at the output's maximum (code 255)
    double mean_level = 0.0;  // mean display level (the mean of the encoded components, 0..1)
};

// The 8-bit RGBA codes of a PNG, as written.
std::vector<uint8_t> png_codes(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.nchannels, 4);
    std::vector<uint8_t> codes(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, codes.data()));
    return codes;
}

// The pixels of the PNG whose radiance (the EXR) is lit: at least `contrast` times the 95th
// percentile of the frame's pixels that are not black, and not the Sun's disc (over 1000 times it).
DisplayedPart displayed_lit_part(const std::string& dir, int frame, double contrast) {
    const Image radiance = read_image_radiance(dir + "/" + frame_file_name(frame, "exr"));
    const std::vector<uint8_t> png = png_codes(dir + "/" + frame_file_name(frame, "png"));
    const size_t n = static_cast<size_t>(radiance.width) * radiance.height;
    auto lum = [&](size_t i) {
        return shading::rec709_luminance(
            glm::vec3(radiance.rgba[4 * i], radiance.rgba[4 * i + 1], radiance.rgba[4 * i + 2]));
    };
    std::vector<float> seen;
    for (size_t i = 0; i < n; ++i)
        if (lum(i) > 0.0f) seen.push_back(lum(i));
    if (seen.empty()) return {};
    std::nth_element(seen.begin(), seen.begin() + static_cast<long>(0.95 * (seen.size() - 1)), seen.end());
    const double p95 = seen[static_cast<size_t>(0.95 * (seen.size() - 1))];
    DisplayedPart d;
    for (size_t i = 0; i < n; ++i) {
        if (lum(i) < contrast * p95 || lum(i) > 1e3 * p95) continue;
        ++d.pixels;
        const uint8_t* p = &png[4 * i];
        if (std::max({p[0], p[1], p[2]}) == 255) ++d.at_maximum;
        d.mean_level += (p[0] + p[1] + p[2]) / (3.0 * 255.0);
    }
    if (d.pixels > 0) d.mean_level /= d.pixels;
    return d;
}

}  // namespace

// The exposure a show producer accepts: from orbit the Earth's lit disc is neither burnt white
// nor dim (at most 2 % of its pixels at the output's maximum, a mean display level in 0.25 ..
// 0.65), and at sunset the sky by the Sun rolls off at its own hue, never clipped per channel.
TEST(AtmosphereDescent, TheEarthFromOrbitIsExposedAndTheSunsetRollsOff) {
    const std::string out = run_descent("atmosphere_descent_exposure", 128, {"exr", "png"}, 47884);
    ASSERT_FALSE(HasFailure());
    const DisplayedPart orbit = displayed_lit_part(out + "/sunset", 0, 1e-2);
    std::printf("orbit: %d lit pixels, %d at the maximum, mean display level %.3f\n", orbit.pixels, orbit.at_maximum,
                orbit.mean_level);
    ASSERT_GT(orbit.pixels, 500);
    EXPECT_LE(orbit.at_maximum, 0.02 * orbit.pixels);
    EXPECT_GE(orbit.mean_level, 0.25);
    EXPECT_LE(orbit.mean_level, 0.65);
    // At sunset (the last frame): every displayed colour that is not white keeps the hue of its
    // exposed scene colour, however bright.
    FrameMetadata meta;
    const Image radiance = read_image_radiance(out + "/sunset/" + frame_file_name(kFrames - 1, "exr"), &meta);
    ASSERT_GT(meta.tone_white, 0.0);
    const DisplayedPart sunset = displayed_lit_part(out + "/sunset", kFrames - 1, 1e-2);
    std::printf("sunset: exposure %.4g white %.4g adapted %.4g cd/m2; %d of %d lit pixels at the maximum\n",
                meta.exposure, meta.tone_white, meta.adapted_cd_m2, sunset.at_maximum, sunset.pixels);
    const std::vector<uint8_t> png = png_codes(out + "/sunset/" + frame_file_name(kFrames - 1, "png"));
    int checked = 0;
    for (size_t i = 0; i < radiance.rgba.size() / 4; ++i) {
        const glm::vec3 c = glm::vec3(radiance.rgba[4 * i], radiance.rgba[4 * i + 1], radiance.rgba[4 * i + 2]) *
                            static_cast<float>(meta.exposure);
        const glm::vec3 shown(srgb_to_linear(png[4 * i] / 255.0f), srgb_to_linear(png[4 * i + 1] / 255.0f),
                              srgb_to_linear(png[4 * i + 2] / 255.0f));
        const float y = shading::rec709_luminance(c), ys = shading::rec709_luminance(shown);
        // Saturated enough for 8 bits to show a hue, and not white.
        if (ys > 0.9f || ys < 0.1f || glm::length(shown - glm::vec3(ys)) < 0.25f * ys) continue;
        const glm::vec3 dc = glm::normalize(c - glm::vec3(y)), ds = glm::normalize(shown - glm::vec3(ys));
        EXPECT_GT(glm::dot(dc, ds), 0.99f) << "pixel " << i;
        ++checked;
    }
    std::printf("sunset: the hue of %d saturated pixels checked\n", checked);
    EXPECT_GT(checked, 100);
}

// One exposure, display white and adaptation for the whole cluster: bit-identical in every
// channel's frame metadata, frame after frame, and the master's own.
TEST(AtmosphereDescent, ExposureWhiteAndAdaptationAreTheSameInEveryChannel) {
    const std::string out = run_descent("atmosphere_descent_cluster", 32, {"exr"}, 47888, true);
    ASSERT_FALSE(HasFailure());
    std::map<int, nlohmann::json> sent;
    for (const auto& e : test::read_events(out + "/logs/events.jsonl"))
        if (e.value("event", "") == "frame") sent[e.at("frame").get<int>()] = e;
    // The adaptation is the master's, frame after frame: the eye stepped from each frame's
    // metering (recomputed here from the show) by the frame interval, starting adapted.
    const ClusterConfig cfg = load_cluster_config(out + "/../cluster.json");
    const SceneConfig scene = load_scene_config(cfg.scene_file);
    const ShowScript show = ShowScript::load(cfg.show_file, scene);
    const AutoExposure ae(cfg, scene);
    EyeAdaptation eye;
    double lowest = 1e30, highest = 0.0;
    for (int f = 0; f < kFrames; ++f) {
        FrameMetadata a, b;
        read_image(out + "/sunset/" + frame_file_name(f, "exr"), &a);
        read_image(out + "/side/" + frame_file_name(f, "exr"), &b);
        ASSERT_TRUE(sent.count(f)) << "frame " << f;
        EXPECT_EQ(static_cast<float>(a.exposure), static_cast<float>(b.exposure)) << f;
        EXPECT_EQ(static_cast<float>(a.tone_white), static_cast<float>(b.tone_white)) << f;
        EXPECT_EQ(static_cast<float>(a.adapted_cd_m2), static_cast<float>(b.adapted_cd_m2)) << f;
        EXPECT_EQ(static_cast<float>(a.exposure), sent[f]["exposure"].get<float>()) << f;
        EXPECT_EQ(static_cast<float>(a.tone_white), sent[f]["tone_white"].get<float>()) << f;
        EXPECT_EQ(static_cast<float>(a.adapted_cd_m2), sent[f]["adapted_cd_m2"].get<float>()) << f;
        EXPECT_GT(a.tone_white, 0.0) << f;
        const Snapshot snap = make_frame_snapshot(cfg, scene, show, static_cast<uint64_t>(f));
        const double expected =
            eye.step(adaptation_target(ae.meter(snap)), show_frame_interval_s(cfg, show), cfg.output.auto_exposure);
        EXPECT_NEAR(a.adapted_cd_m2, expected, 1e-5 * expected) << f;
        lowest = std::min(lowest, a.adapted_cd_m2);
        highest = std::max(highest, a.adapted_cd_m2);
    }
    EXPECT_GT(highest, lowest) << "the eye adapted during the flight";
}
