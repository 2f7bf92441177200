// The slave's output stage (slave/output/) with real sinks: frame files, an X11 window on a real
// X server (Xvfb) through EGL, and the KMS sink's checks that need no DRM device. The KMS sink
// itself needs /dev/dri, which CI machines lack: its test skips, saying so.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <set>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "output/kms_display.hpp"
#include "output/output_surface.hpp"
#include "output/projector_output.hpp"
#include "scene_renderer.hpp"
#include "support/cluster_fixture.hpp"
#include "support/test_support.hpp"
#include "support/xvfb_display.hpp"

using namespace cupola;

namespace {

constexpr double kAu = 1.495978707e11;
constexpr int kWidth = 96, kHeight = 64;

// The Sun to the side and a white moon ahead: a half-lit disc, so the frame holds a smooth ramp
// of values from black to bright (every encoding step is exercised, not just 0 and 255).
// One folder per test case: ctest runs the cases as parallel processes, and a shared folder,
// emptied as each starts, lost one case's texture to another's start.
SceneConfig moon_scene() {
    const std::string dir = test::scratch_dir(std::string("OutputSinks_scene_") +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) hdr += std::string("\x80\x80\x80\x81", 4);  // RGBE 1.0
    test::write_text(dir + "/white.hdr", hdr);
    test::write_text(dir + "/stars.csv", "ra_deg,dec_deg,vmag,bv,name\n10.0,10.0,5.0,0.6,Faint\n");
    test::write_text(dir + "/scene.json", R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 5.8e4 },
        { "name": "moon", "kind": "moon", "ephemeris": "moon", "radius_m": 2.6e5, "texture": "white.hdr",
          "albedo": 0.5 } ],
      "stars": { "catalog": "stars.csv", "magnitude_limit": -2.0 } })");
    return load_scene_config(dir + "/scene.json");
}

struct MoonView {
    SceneConfig scene = moon_scene();
    ClusterConfig cluster;
    ChannelConfig channel;
    MoonView() {
        channel.name = "test";
        channel.width = kWidth;
        channel.height = kHeight;
        channel.fov = FovDeg{3, 3, 2, 2};
        cluster.channels = {channel};
    }
    Snapshot snapshot(uint64_t frame, float exposure) const {
        Snapshot s;
        s.frame = frame;
        s.settings.exposure = exposure;
        const double a = 0.2 * static_cast<double>(frame);  // the moon drifts: frames differ
        s.bodies = {BodyState{0, glm::dvec3(kAu, 0.0, 0.3 * kAu), {1, 0, 0, 0}},
                    BodyState{1, glm::dvec3(1.0e5 * a, 0.0, -1.0e7), {1, 0, 0, 0}}};
        return s;
    }
};

FrameMetadata meta_of(const Snapshot& s) {
    FrameMetadata m;
    m.channel_id = 0;
    m.channel_name = "test";
    m.frame = s.frame;
    return m;
}

// The exposure that puts the brightest pixel of a frame at 0.9 (a ramp over the whole range).
float exposure_for(SceneRenderer& r, const MoonView& v) {
    const Image img = r.render(v.snapshot(1, 1.0f));
    float peak = 0.0f;
    for (size_t i = 0; i < img.rgba.size(); i += 4) peak = std::max(peak, img.rgba[i + 1]);
    EXPECT_GT(peak, 0.0f) << "the moon is not in view";
    return peak > 0.0f ? 0.9f / peak : 1.0f;
}

// The bytes of an 8-bit image file, as stored.
EncodedImage read_bytes(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    EncodedImage img;
    if (!in) return img;
    img.width = in->spec().width;
    img.height = in->spec().height;
    EXPECT_EQ(in->spec().nchannels, 4);
    img.rgba.resize(static_cast<size_t>(img.width) * img.height * 4);
    EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, img.rgba.data()));
    return img;
}

// One X server for the whole program, stopped at exit: servers started and stopped in quick
// succession on the same display number were seen to refuse a connection now and then.
test::XvfbDisplay& xvfb() {
    static test::XvfbDisplay x(kWidth, kHeight);
    return x;
}

SinkConfig window_sinks(const std::string& display, std::vector<std::string> names) {
    SinkConfig s;
    s.sinks = std::move(names);
    s.window.display = display;
    return s;
}

}  // namespace

// The acceptance check of the window sink: what the window shows after the swap (XGetImage)
// is, byte for byte in R, G and B, the files sink's PNG of the same frame (the window has no
// alpha). Exact because both are the warp pass's one encoded RGBA8 target: the window gets it
// by a same-size blit, the PNG by a read-back of the same texture.
TEST(OutputSinks, WindowShowsExactlyTheFilesSinkPng) {
    test::XvfbDisplay& x = xvfb();
    if (!x.skip_reason().empty()) GTEST_SKIP() << x.skip_reason();
    MoonView v;
    OutputSurface surface(window_sinks(x.name(), {"window", "files"}), -1, kWidth, kHeight);
    EXPECT_EQ(surface.egl().info().platform, "x11");
    ASSERT_NE(surface.window(), nullptr);
    EXPECT_EQ(surface.window()->rect().width, kWidth);  // fullscreen on the whole screen
    SceneRenderer renderer(v.cluster, v.channel, v.scene);
    const float exposure = exposure_for(renderer, v);
    const std::string dir = test::scratch_dir("OutputSinks_window_png");
    ProjectorOutput output(surface, window_sinks(x.name(), {"window", "files"}), FilesOutput{dir, {"png"}},
                           std::nullopt, kWidth, kHeight);
    EXPECT_TRUE(output.has_live_output());
    for (uint64_t frame = 2; frame <= 3; ++frame) {
        const Snapshot snap = v.snapshot(frame, exposure);
        renderer.draw(snap);
        output.take(renderer, meta_of(snap), exposure);
        output.present(frame);
        const EncodedImage shown = surface.window()->read_pixels();
        output.finish();
        const EncodedImage png = read_bytes(dir + "/" + frame_file_name(frame, "png"));
        ASSERT_EQ(shown.width, png.width);
        ASSERT_EQ(shown.height, png.height);
        std::set<int> levels;
        size_t differing = 0;
        for (size_t i = 0; i < png.rgba.size(); i += 4)
            for (int c = 0; c < 3; ++c) {
                levels.insert(png.rgba[i + c]);
                if (shown.rgba[i + c] != png.rgba[i + c]) ++differing;
            }
        EXPECT_EQ(differing, 0u) << "frame " << frame;
        EXPECT_GT(levels.size(), 40u) << "the frame should be a ramp, not a few flat levels";
        if (frame == 3) write_encoded_png(test::scratch_dir("OutputSinks_screenshot"), shown, meta_of(snap), exposure);
    }
    EXPECT_EQ(output.presents(), 2u);
}

// A slave whose only sink is a window reads nothing back to the CPU: no glReadPixels of the
// channel render or of the projector frame, yet the frame reaches the window.
TEST(OutputSinks, WindowOnlyReadsNothingBack) {
    test::XvfbDisplay& x = xvfb();
    if (!x.skip_reason().empty()) GTEST_SKIP() << x.skip_reason();
    MoonView v;
    const SinkConfig sinks = window_sinks(x.name(), {"window"});
    OutputSurface surface(sinks, -1, kWidth, kHeight);
    SceneRenderer renderer(v.cluster, v.channel, v.scene);
    ProjectorOutput output(surface, sinks, FilesOutput{test::scratch_dir("OutputSinks_unused"), {"png"}}, std::nullopt,
                           kWidth, kHeight);
    for (uint64_t frame = 1; frame <= 3; ++frame) {
        const Snapshot snap = v.snapshot(frame, 2.0e3f);
        renderer.draw(snap);
        output.take(renderer, meta_of(snap), 2.0e3);
        output.present(frame);
    }
    EXPECT_EQ(renderer.read_backs(), 0u);
    EXPECT_EQ(output.read_backs(), 0u);
    EXPECT_EQ(output.presents(), 3u);
    const EncodedImage shown = surface.window()->read_pixels();
    int lit = 0;
    for (size_t i = 0; i < shown.rgba.size(); i += 4) lit += shown.rgba[i + 1] > 0;
    EXPECT_GT(lit, 50) << "the moon should be on the window";
}

// Files only, no calibration: no warp pass, and the files are today's (the channel render read
// back once per frame and encoded on the CPU): the same bytes as write_frame of render().
TEST(OutputSinks, FilesOnlyWritesTheChannelRenderAsBefore) {
    MoonView v;
    unsetenv("DISPLAY");
    SinkConfig sinks;
    OutputSurface surface(sinks, -1, kWidth, kHeight);
    EXPECT_NE(surface.egl().info().platform, "x11");
    SceneRenderer renderer(v.cluster, v.channel, v.scene);
    const std::string dir = test::scratch_dir("OutputSinks_files"), ref = test::scratch_dir("OutputSinks_files_ref");
    const Snapshot snap = v.snapshot(4, 2.0e3f);
    write_frame(ref, renderer.render(snap), meta_of(snap), {"png", "exr"}, 2.0e3);
    ProjectorOutput output(surface, sinks, FilesOutput{dir, {"png", "exr"}}, std::nullopt, kWidth, kHeight);
    EXPECT_FALSE(output.warps());
    EXPECT_FALSE(output.has_live_output());
    const uint64_t before = renderer.read_backs();
    renderer.draw(snap);
    output.take(renderer, meta_of(snap), 2.0e3);
    output.present(4);
    EXPECT_EQ(output.finish(), 0u);
    EXPECT_EQ(renderer.read_backs(), before);  // not the synchronous read-back...
    EXPECT_EQ(output.read_backs(), 1u);        // ...one asynchronous one, shared by the PNG and the EXR
    for (const char* ext : {"png", "exr"}) {
        const Image a = read_image(dir + "/" + frame_file_name(4, ext)),
                    b = read_image(ref + "/" + frame_file_name(4, ext));
        EXPECT_EQ(a.rgba, b.rgba) << ext;
    }
}

// The window covers the RandR output it names; an output that does not exist is an error naming
// the field and listing the outputs there are.
TEST(OutputSinks, WindowCoversTheNamedRandROutput) {
    test::XvfbDisplay& x = xvfb();
    if (!x.skip_reason().empty()) GTEST_SKIP() << x.skip_reason();
    SinkConfig sinks = window_sinks(x.name(), {"window"});
    sinks.window.output_name = "NO-SUCH-1";
    try {
        X11Window w(sinks.window, kWidth, kHeight);
        FAIL() << "no error for an unknown output";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("output.window.output_name \"NO-SUCH-1\""), std::string::npos) << what;
        const size_t list = what.find("outputs: ");
        ASSERT_NE(list, std::string::npos) << what;
        // Xvfb has one output: cover it by name.
        std::string first = what.substr(list + 9);
        first = first.substr(0, first.find_first_of(",)"));
        sinks.window.output_name = first;
        X11Window named(sinks.window, kWidth / 2, kHeight / 2);
        EXPECT_EQ(named.rect().width, kWidth) << first;
        EXPECT_EQ(named.rect().height, kHeight) << first;
    }
    sinks.window.output_name.clear();
    sinks.window.fullscreen = false;
    X11Window small(sinks.window, 40, 30);
    EXPECT_EQ(small.rect().width, 40);
    EXPECT_EQ(small.rect().height, 30);
}

TEST(OutputSinks, UnreachableDisplayNamesTheField) {
    WindowOutputConfig w;
    w.display = ":987";
    try {
        X11Window win(w, kWidth, kHeight);
        FAIL() << "display :987 opened";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("output.window.display \":987\""), std::string::npos) << e.what();
    }
}

// The KMS sink needs a DRM device with a connected display; these machines have no /dev/dri.
TEST(OutputSinks, KmsSinkShowsFrames) {
    if (!std::filesystem::exists("/dev/dri/card0"))
        GTEST_SKIP() << "no /dev/dri/card0 on this machine: the KMS sink needs a DRM device (none in CI)";
    KmsOutputConfig k;
    KmsDisplay display(k);
    EXPECT_GT(display.width(), 0);
    SinkConfig sinks;
    sinks.sinks = {"kms"};
    OutputSurface surface(sinks, -1, display.width(), display.height());
    EXPECT_EQ(surface.egl().info().platform, "gbm");
}

TEST(OutputSinks, KmsDeviceThatCannotOpenNamesTheField) {
    KmsOutputConfig k;
    k.device = test::scratch_dir("OutputSinks_kms") + "/card9";
    try {
        KmsDisplay d(k);
        FAIL() << "opened " << k.device;
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("output.kms.device \"" + k.device + "\": cannot open"), std::string::npos)
            << e.what();
    }
    // A file that is not a DRM device: opened, but it has no mode-setting resources.
    k.device = test::scratch_dir("OutputSinks_kms") + "/not_a_device";
    test::write_text(k.device, "x");
    try {
        KmsDisplay d(k);
        FAIL() << "a plain file taken as a DRM device";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("output.kms.device"), std::string::npos) << e.what();
    }
}

namespace {
std::string config_error(const nlohmann::json& overrides) {
    const std::string dir = test::scratch_dir("OutputSinks_config");
    try {
        load_cluster_config(test::write_test_cluster(dir, 47000, 64, 64, overrides));
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(OutputSinksConfig, BadSinkConfigNamesTheField) {
    using nlohmann::json;
    const std::string unknown = config_error(json::parse(R"({"output": {"sink": "hdmi"}})"));
    EXPECT_NE(unknown.find("output.sink"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("hdmi"), std::string::npos) << unknown;
    const std::string in_list = config_error(json::parse(R"({"output": {"sink": ["files", "vga"]}})"));
    EXPECT_NE(in_list.find("output.sink[1]"), std::string::npos) << in_list;
    const std::string no_display = config_error(json::parse(R"({"output": {"sink": "window"}})"));
    EXPECT_NE(no_display.find("output.window.display"), std::string::npos) << no_display;
    for (const char* mode : {"1920x", "1920x1080@", "axb", "1920x1080@60Hz", "0x1080"}) {
        const std::string bad = config_error({{"output", {{"sink", "kms"}, {"kms", {{"mode", mode}}}}}});
        EXPECT_NE(bad.find("output.kms.mode"), std::string::npos) << mode << ": " << bad;
    }
    const std::string both = config_error(json::parse(R"({"output": {"sink": ["window", "kms"],
        "window": {"display": ":0"}}})"));
    EXPECT_NE(both.find("output.sink"), std::string::npos) << both;
    EXPECT_NE(both.find("cannot run in one slave"), std::string::npos) << both;
}

TEST(OutputSinksConfig, ChannelSinksOverTheClusters) {
    const std::string dir = test::scratch_dir("OutputSinks_config_ok");
    nlohmann::json o = nlohmann::json::parse(R"({"output": {"sink": ["files", "kms"],
        "kms": {"connector": "HDMI-A-1", "mode": "1920x1080@59.94"}}})");
    nlohmann::json c = nlohmann::json::parse(test::read_text(test::source_path("configs/dome-4ch.json")))["channels"];
    c[1]["output"] = nlohmann::json::parse(R"({"sink": "window", "window": {"display": ":3", "output_name": "DP-2"}})");
    o["channels"] = c;
    const ClusterConfig cfg = load_cluster_config(test::write_test_cluster(dir, 47010, 64, 64, o));
    const SinkConfig& a = cfg.channels[0].output;
    EXPECT_EQ(a.sinks, (std::vector<std::string>{"files", "kms"}));
    EXPECT_EQ(a.kms.connector, "HDMI-A-1");
    EXPECT_EQ(a.kms.device, "/dev/dri/card0");
    EXPECT_EQ(a.kms.mode_width, 1920);
    EXPECT_EQ(a.kms.mode_height, 1080);
    EXPECT_DOUBLE_EQ(a.kms.mode_refresh_hz, 59.94);
    const SinkConfig& b = cfg.channels[1].output;
    EXPECT_EQ(b.sinks, (std::vector<std::string>{"window"}));
    EXPECT_EQ(b.window.display, ":3");
    EXPECT_EQ(b.window.output_name, "DP-2");
    EXPECT_TRUE(b.window.fullscreen);
    const ClusterConfig plain = load_cluster_config(test::write_test_cluster(dir, 47020, 64, 64));
    EXPECT_EQ(plain.channels[0].output.sinks, (std::vector<std::string>{"files"}));
    const std::string bad =
        config_error({{"channels",
                       {{{"id", 0},
                         {"orientation", nlohmann::json::object()},
                         {"fov", {{"left_deg", 40}, {"right_deg", 40}, {"up_deg", 40}, {"down_deg", 40}}},
                         {"output", {{"sink", "kms"}, {"kms", {{"mode", "big"}}}}}}}},
                      {"dome", {{"require_full_coverage", false}}}});
    EXPECT_NE(bad.find("channels[0].output.kms.mode"), std::string::npos) << bad;
}

namespace {

// A headless context for the files sink on its own.
struct HeadlessChannel {
    MoonView v;
    OutputSurface surface{SinkConfig{}, -1, kWidth, kHeight};
    SceneRenderer renderer{v.cluster, v.channel, v.scene};
    uint64_t sync_reads = 0;  // ProjectorFrame's counter of synchronous reads (none expected)
};

Image read_file_raw(const std::string& path) {
    FrameMetadata m;
    return read_image(path, &m);
}

}  // namespace

// The files sink reads the channel render back through its ring of pixel buffers: take() only
// queues the read (at most two frames wait), the frames come out in the order taken, and each
// file holds exactly what the synchronous glReadPixels of the same frame gives (write_frame of
// read_back()), for frames that differ from each other.
TEST(OutputSinks, FilesSinkPixelBuffersKeepOrderAndMatchTheSynchronousRead) {
    unsetenv("DISPLAY");
    HeadlessChannel h;
    const std::string dir = test::scratch_dir("OutputSinks_pbo"), ref = test::scratch_dir("OutputSinks_pbo_ref");
    constexpr float kExposure = 2.0e3f;
    {
        FilesSink files(dir, {"exr", "png"}, 2);
        for (uint64_t frame = 1; frame <= 6; ++frame) {
            const Snapshot snap = h.v.snapshot(frame, kExposure);
            h.renderer.draw(snap);
            write_frame(ref, h.renderer.read_back(), meta_of(snap), {"exr", "png"}, kExposure);
            files.take(ProjectorFrame(h.renderer, nullptr, meta_of(snap), kExposure, h.sync_reads));
            EXPECT_LE(files.frames_pending(), 2u) << "frame " << frame;
            EXPECT_GE(files.frames_pending(), 1u) << "take() should not wait for its own read";
        }
        EXPECT_EQ(files.read_backs(), 6u);  // one float read per frame, shared by the EXR and the PNG
        EXPECT_EQ(files.finish(), 0u);
        EXPECT_EQ(files.frames_pending(), 0u);
        EXPECT_EQ(files.written_frames(), (std::vector<uint64_t>{1, 2, 3, 4, 5, 6}));
    }
    EXPECT_EQ(h.sync_reads, 0u);
    for (uint64_t frame = 1; frame <= 6; ++frame)
        for (const char* ext : {"exr", "png"}) {
            FrameMetadata m;
            const Image got = read_image(dir + "/" + frame_file_name(frame, ext), &m);
            EXPECT_EQ(m.frame, frame);
            EXPECT_EQ(got.rgba, read_file_raw(ref + "/" + frame_file_name(frame, ext)).rgba) << frame << " " << ext;
        }
    EXPECT_NE(read_file_raw(dir + "/" + frame_file_name(1, "exr")).rgba,
              read_file_raw(dir + "/" + frame_file_name(2, "exr")).rgba)
        << "the frames should differ, or the order check proves nothing";
}

// When the warp pass ran, the EXR is read as RGBA float from its linear target and the PNG as
// RGBA8 from its encoded target (a quarter of the bytes), both through pixel buffers: the files
// equal the warp pass's synchronous reads, bit for bit.
TEST(OutputSinks, FilesSinkReadsTheProjectorFrameInTheFormatsItStores) {
    unsetenv("DISPLAY");
    HeadlessChannel h;
    const std::string dir = test::scratch_dir("OutputSinks_pbo_warp");
    constexpr float kExposure = 2.0e3f;
    WarpPass warp(std::nullopt, kWidth, kHeight);
    std::vector<Image> linear;
    std::vector<std::vector<uint8_t>> encoded;
    {
        FilesSink files(dir, {"exr", "png"}, 1);
        for (uint64_t frame = 1; frame <= 3; ++frame) {
            const Snapshot snap = h.v.snapshot(frame, kExposure);
            h.renderer.draw(snap);
            warp.draw(h.renderer.color().id(), kExposure);
            linear.push_back(warp.read_linear());
            encoded.push_back(warp.read_encoded());
            files.take(ProjectorFrame(h.renderer, &warp, meta_of(snap), kExposure, h.sync_reads));
        }
        EXPECT_EQ(files.read_backs(), 6u);  // a float and a byte read per frame
        EXPECT_EQ(files.finish(), 0u);
    }
    for (uint64_t frame = 1; frame <= 3; ++frame) {
        const Image exr = read_file_raw(dir + "/" + frame_file_name(frame, "exr"));
        EXPECT_EQ(exr.rgba, linear[frame - 1].rgba) << frame;
        const EncodedImage png = read_bytes(dir + "/" + frame_file_name(frame, "png"));
        EXPECT_EQ(png.rgba, encoded[frame - 1]) << frame;
    }
}
