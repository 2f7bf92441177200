// Scene test: a real loopback run (master + slave processes, UDP, EGL, EXR files) flies
// from 400 km down to 1 km toward a sunset (configs/descent-1ch.json, auto exposure). The
// atmosphere must not jump where the camera enters it (60 km, exactly at show time 3 s): the
// frame-to-frame change there must be no larger than the largest change elsewhere in the flight.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "config/cluster_config.hpp"
#include "image/frame_image.hpp"
#include "support/cluster_fixture.hpp"
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
}  // namespace

TEST(AtmosphereDescent, NoDiscontinuityWhereTheCameraEntersTheAtmosphere) {
    const std::string dir = test::scratch_dir("atmosphere_descent");
    setenv("CUPOLA_CACHE_DIR", (dir + "/cache").c_str(), 1);
    nlohmann::json c = nlohmann::json::parse(test::read_text(test::source_path("configs/descent-1ch.json")));
    for (const char* k : {"key_file", "scene", "show"}) c[k] = test::source_path("configs/" + c[k].get<std::string>());
    c["network"]["report_port"] = 47881;
    c["channels"][0]["unicast_address"] = "127.0.0.1:47880";
    c["network"]["channel_timeout_ms"] = 30000;
    c["network"]["hello_wait_ms"] = 60000;
    c["output"]["width"] = 64;
    c["output"]["height"] = 64;
    c["output"]["formats"] = {"exr"};
    const std::string config = dir + "/cluster.json";
    test::write_text(config, c.dump(2));
    const std::string out = dir + "/out";
    ChildProcess p({test::bin_path("cupola-loopback"), "--config", config, "--frames", std::to_string(kFrames), "--out",
                    out, "--timeout", "400", "--no-stitch"},
                   dir + "/loopback.log", {"DISPLAY", "WAYLAND_DISPLAY", "SPDLOG_LEVEL"});
    ASSERT_EQ(p.wait_for(std::chrono::seconds(420)).value_or(-1), 0) << test::read_text(dir + "/loopback.log");

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
