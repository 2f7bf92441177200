// The alignment patterns (docs/ALIGNMENT.md): the control command and the show event that switch
// them, their way into the snapshot, and the pattern pass on a real headless EGL context
// (llvmpipe on CI) in 128-pixel channels: the grid at the dome directions ChannelFrustum gives,
// the fine lines near the springline, the label, the overlap tint, the white and black fields,
// and the same lines where two channels overlap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "config/cluster_config.hpp"
#include "config/config_error.hpp"
#include "config/scene_config.hpp"
#include "control/control_command.hpp"
#include "director.hpp"
#include "eclipse/shadow_casters.hpp"
#include "gl/egl_context.hpp"
#include "master_node.hpp"
#include "passes/pattern_pass.hpp"
#include "passes/text_raster.hpp"
#include "scene_renderer.hpp"
#include "shading/shared_shading.hpp"
#include "support/test_support.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;

namespace {

std::string parse_error(const std::string& line) {
    try {
        parse_control_line(line);
    } catch (const ControlError& e) {
        return e.what();
    }
    return "(accepted)";
}

// A show of one keyframe and the given events (a JSON array).
ShowScript show_with_events(const SceneConfig& scene, const std::string& name, const std::string& events) {
    const std::string dir = test::scratch_dir(name);
    test::write_text(dir + "/show.json", R"({"frame_interval_s": 0.5, "keyframes":[
        {"at_s":0,"time_utc":"2024-04-08T12:00:00Z","camera":{"anchor":"earth","offset_m":[2e7,0,0],"look_at":"earth"}}],
        "events": )" + events + "}");
    return ShowScript::load(dir + "/show.json", scene);
}

std::string show_error_field(const SceneConfig& scene, const std::string& events) {
    try {
        show_with_events(scene, "pattern_bad_event", events);
    } catch (const ConfigError& e) {
        return e.field();
    }
    return "(accepted)";
}

}  // namespace

TEST(AlignmentPatternCommand, ParsesAndNamesWhatWasWrong) {
    auto c = parse_control_line("pattern grid");
    EXPECT_EQ(c.verb, ControlVerb::Pattern);
    EXPECT_EQ(c.pattern, "grid");
    EXPECT_EQ(parse_control_line("  PATTERN White ").pattern, "white");
    EXPECT_EQ(parse_control_line("pattern black").pattern, "black");
    EXPECT_EQ(parse_control_line("pattern off").pattern, "off");
    EXPECT_EQ(parse_control_line("pattern show").pattern, "show");
    EXPECT_NE(parse_error("pattern").find("usage: pattern grid|white|black|off|show"), std::string::npos);
    EXPECT_NE(parse_error("pattern grid white").find("usage: pattern"), std::string::npos);
    EXPECT_NE(parse_error("pattern stripes").find("\"stripes\" is not one of grid, white, black, off, show"),
              std::string::npos);
    EXPECT_NE(control_help().find("pattern grid|white|black|off|show"), std::string::npos);
}

TEST(AlignmentPatternCommand, ReachesTheSnapshotFromTheFrameTheReplyNames) {
    ClusterConfig cluster = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    cluster.frame_rate_hz = 0;
    const SceneConfig scene = load_scene_config(cluster.scene_file);
    Director director(cluster, scene, ShowScript::load(cluster.show_file, scene));
    const NavSample none;
    EXPECT_EQ(alignment_pattern_of(director.frame(0, none).snapshot.settings.flags), AlignmentPattern::Off);
    EXPECT_EQ(director.apply(parse_control_line("pattern grid"), 5), "pattern grid from frame 5");
    const Snapshot s5 = director.frame(5, none).snapshot;
    EXPECT_EQ(alignment_pattern_of(s5.settings.flags), AlignmentPattern::Grid);
    EXPECT_EQ(shadow_mode_of(s5.settings.flags), scene.shadows.mode);  // the other bits keep their meaning
    EXPECT_EQ(director.status(6).at("pattern"), "grid");
    EXPECT_EQ(director.apply(parse_control_line("pattern white"), 7), "pattern white from frame 7");
    EXPECT_EQ(alignment_pattern_of(director.frame(7, none).snapshot.settings.flags), AlignmentPattern::White);
    director.apply(parse_control_line("set shadow_mode illustrative"), 8);
    const Snapshot s8 = director.frame(8, none).snapshot;
    EXPECT_EQ(alignment_pattern_of(s8.settings.flags), AlignmentPattern::White);
    EXPECT_EQ(shadow_mode_of(s8.settings.flags), ShadowMode::Illustrative);
    EXPECT_EQ(director.apply(parse_control_line("pattern show"), 9), "pattern show (off now) from frame 9");
    EXPECT_EQ(alignment_pattern_of(director.frame(9, none).snapshot.settings.flags), AlignmentPattern::Off);
    // Stopping the show keeps the override.
    director.apply(parse_control_line("pattern black"), 10);
    director.apply(parse_control_line("stop"), 10);
    EXPECT_EQ(alignment_pattern_of(director.frame(10, none).snapshot.settings.flags), AlignmentPattern::Black);
}

TEST(AlignmentPatternShow, EventsSwitchThePatternAndBadOnesNameTheField) {
    const SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const ShowScript show = show_with_events(scene, "pattern_events", R"([
        {"at_s": 2, "pattern": "grid"},
        {"at_s": 4, "pattern": "white", "exposure": 3.0},
        {"at_s": 6, "pattern": "black"},
        {"at_s": 8, "pattern": "off"}])");
    EXPECT_FALSE(show.settings_at(1.9).pattern);
    EXPECT_EQ(alignment_pattern_of(show.evaluate(1.9, scene).settings.flags), AlignmentPattern::Off);
    EXPECT_EQ(alignment_pattern_of(show.evaluate(2.0, scene).settings.flags), AlignmentPattern::Grid);
    EXPECT_EQ(alignment_pattern_of(show.evaluate(5.0, scene).settings.flags), AlignmentPattern::White);
    EXPECT_EQ(alignment_pattern_of(show.evaluate(7.0, scene).settings.flags), AlignmentPattern::Black);
    EXPECT_EQ(alignment_pattern_of(show.evaluate(9.0, scene).settings.flags), AlignmentPattern::Off);

    // The master's snapshot, and a command over the show's pattern until "pattern show".
    ClusterConfig cluster = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    cluster.frame_rate_hz = 0;  // frame N = show time N x 0.5 s
    EXPECT_EQ(alignment_pattern_of(make_frame_snapshot(cluster, scene, show, 5).settings.flags),
              AlignmentPattern::Grid);
    Director director(cluster, scene, show);
    const NavSample none;
    EXPECT_EQ(alignment_pattern_of(director.frame(5, none).snapshot.settings.flags), AlignmentPattern::Grid);
    director.apply(parse_control_line("pattern off"), 6);
    EXPECT_EQ(alignment_pattern_of(director.frame(9, none).snapshot.settings.flags), AlignmentPattern::Off);
    EXPECT_EQ(director.apply(parse_control_line("pattern show"), 10), "pattern show (white now) from frame 10");
    EXPECT_EQ(alignment_pattern_of(director.frame(10, none).snapshot.settings.flags), AlignmentPattern::White);

    EXPECT_EQ(show_error_field(scene, R"([{"at_s": 1, "pattern": "stripes"}])"), "events[0].pattern");
    EXPECT_EQ(show_error_field(scene, R"([{"at_s": 1, "pattern": 2}])"), "events[0].pattern");
    EXPECT_EQ(show_error_field(scene, R"([{"at_s": 1, "pattern": "grid"}])"), "(accepted)");
}

TEST(AlignmentPatternWire, EveryPatternRoundTripsInTheSettingsFlags) {
    for (const std::string& name : alignment_pattern_names()) {
        Snapshot s;
        s.frame = 12;
        s.settings.flags =
            with_alignment_pattern(with_shadow_mode(0, ShadowMode::Lookup), alignment_pattern_from_name(name));
        const std::vector<uint8_t> bytes = encode_snapshot(s);
        const Snapshot d = decode_snapshot(bytes.data(), bytes.size());
        EXPECT_EQ(alignment_pattern_name(alignment_pattern_of(d.settings.flags)), name);
        EXPECT_EQ(shadow_mode_of(d.settings.flags), ShadowMode::Lookup);
        EXPECT_EQ(encode_snapshot(Snapshot{}).size(), bytes.size());  // the layout is the same
    }
    EXPECT_THROW(alignment_pattern_from_name("stripes"), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Rendered patterns.

namespace {

// Scratch folders per test: ctest runs the cases in parallel processes.
std::string test_name() { return ::testing::UnitTest::GetInstance()->current_test_info()->name(); }

EglContext& context() {
    static EglContext* ctx = [] {
        unsetenv("DISPLAY");
        unsetenv("WAYLAND_DISPLAY");
        setenv("CUPOLA_CACHE_DIR", test::scratch_dir("AlignmentPattern_cache_" + test_name()).c_str(), 1);
        return new EglContext(-1);
    }();
    return *ctx;
}

constexpr int kSize = 128;
constexpr float kExposure = 2.0f;  // the pattern is divided by it: the written frame shows the pattern
const glm::vec3 kGrey(0.6f);

// Two channels 60 deg apart in azimuth, 80 deg wide: they overlap between about 20 and 40 deg.
struct Cluster {
    ClusterConfig cluster;
    SceneConfig scene;
    Cluster() {
        const std::string dir = test::scratch_dir("AlignmentPattern_" + test_name());
        test::write_text(dir + "/stars.csv", "ra_deg,dec_deg,vmag,bv,name\n10.0,10.0,5.0,0.6,Faint\n");
        test::write_text(dir + "/scene.json", R"({ "bodies": [
            { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 5.8e4 } ],
          "stars": { "catalog": "stars.csv", "magnitude_limit": 6.0 } })");
        scene = load_scene_config(dir + "/scene.json");
        for (int id = 0; id < 2; ++id) {
            ChannelConfig ch;
            ch.id = id;
            ch.name = id == 0 ? "front" : "right";
            ch.orientation = EulerDeg{60.0 * id, 30.0, 0.0};
            ch.fov = FovDeg{40, 40, 40, 40};
            ch.width = ch.height = kSize;
            cluster.channels.push_back(ch);
        }
    }
    const ChannelConfig& channel(int id) const { return cluster.channels[id]; }
};

Snapshot pattern_snapshot(AlignmentPattern p) {
    Snapshot s;
    s.frame = 3;
    s.settings.exposure = kExposure;
    s.settings.flags = with_alignment_pattern(0, p);
    return s;
}

struct Rendered {
    Image image;
    glm::vec4 label_box;  // window pixels, origin at the bottom left
    std::string label;
    glm::vec3 at(int x, int y) const {
        const float* p = image.pixel(x, y);
        return glm::vec3(p[0], p[1], p[2]) * kExposure;
    }
    bool in_label(int x, int y) const {
        const float wx = x + 0.5f, wy = kSize - y - 0.5f;
        return wx >= label_box.x - 1 && wx < label_box.z + 1 && wy >= label_box.y - 1 && wy < label_box.w + 1;
    }
};

Rendered render(const Cluster& c, int id, AlignmentPattern p) {
    context();
    SceneRenderer renderer(c.cluster, c.channel(id), c.scene);
    const PatternPass probe(c.cluster, c.channel(id));
    return {renderer.render(pattern_snapshot(p)), probe.label_box(), probe.label()};
}

// The pixel (image row 0 at the top) whose centre lies nearest to a dome direction; none outside.
std::optional<glm::ivec2> pixel_of(const ChannelFrustum& f, const glm::dvec3& dome_dir) {
    const auto p = f.dome_direction_to_pixel(dome_dir);
    if (!p || p->x < 0 || p->y < 0 || p->x >= f.width() || p->y >= f.height()) return std::nullopt;
    return glm::ivec2(static_cast<int>(p->x), static_cast<int>(p->y));
}

glm::dvec3 dome_dir(double az_deg, double el_deg) {
    const double az = glm::radians(az_deg), el = glm::radians(el_deg);
    return {std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az)};
}

// A point on a line whose pixel centre lies nearest to it, among points along the line (the
// pixel is then covered by the line across its whole width).
glm::ivec2 centred_pixel_on(const ChannelFrustum& f, double az0, double el0, double az1, double el1) {
    double best = 1e9;
    glm::ivec2 out(-1);
    for (int i = 0; i <= 400; ++i) {
        const double t = i / 400.0;
        const auto p = f.dome_direction_to_pixel(dome_dir(az0 + t * (az1 - az0), el0 + t * (el1 - el0)));
        if (!p) continue;
        const glm::dvec2 centre = glm::floor(*p) + 0.5;
        const double d = glm::length(*p - centre);
        if (d < best) best = d, out = glm::ivec2(glm::floor(*p));
    }
    return out;
}

// The grid's value at the centre of a pixel, on the CPU from the shared function.
glm::vec3 cpu_grid(const ChannelFrustum& f, int x, int y) {
    const glm::dvec3 d = f.pixel_to_dome_direction({x + 0.5, y + 0.5});
    const glm::dvec3 v = glm::transpose(f.rotation()) * d;
    const float tan_per_pixel = static_cast<float>((f.tan_left() + f.tan_right()) / f.width());
    const float pixel_rad = shading::grid_pixel_rad(glm::vec2(v.x / -v.z, v.y / -v.z), tan_per_pixel);
    return shading::alignment_grid(glm::vec3(d), pixel_rad);
}

float brightest(const glm::vec3& c) { return std::max({c.r, c.g, c.b}); }

}  // namespace

TEST(AlignmentPatternRender, GridLinesLieAtTheirDomeDirections) {
    const Cluster c;
    const Rendered r = render(c, 0, AlignmentPattern::Grid);
    const ChannelFrustum f = c.channel(0).frustum();
    const ChannelFrustum other = c.channel(1).frustum();
    // On the 40 and 50 deg circles and the -10 deg meridian: bright; between them: dark.
    for (const glm::ivec2 p : {centred_pixel_on(f, -25, 40, -15, 40), centred_pixel_on(f, -25, 50, -15, 50),
                               centred_pixel_on(f, -10, 42, -10, 48)}) {
        ASSERT_GE(p.x, 0);
        ASSERT_FALSE(r.in_label(p.x, p.y));
        EXPECT_GT(brightest(r.at(p.x, p.y)), 0.5f) << "pixel " << p.x << "," << p.y;
    }
    for (const glm::dvec3 d : {dome_dir(-5, 45), dome_dir(-15, 35), dome_dir(-25, 55)}) {
        ASSERT_FALSE(other.contains(d));
        const auto p = pixel_of(f, d);
        ASSERT_TRUE(p);
        EXPECT_LT(brightest(r.at(p->x, p->y)), 0.02f) << "pixel " << p->x << "," << p->y;
    }
    // Every pixel outside the label equals the shared function's value at its centre (the tint
    // where the other channel covers it).
    int compared = 0, differ = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (r.in_label(x, y)) continue;
            glm::vec3 want = cpu_grid(f, x, y);
            if (other.contains(f.pixel_to_dome_direction({x + 0.5, y + 0.5})))
                want = glm::max(want, PatternPass::overlap_tint());
            ++compared;
            if (glm::length(r.at(x, y) - want) > 0.05f) ++differ;
        }
    EXPECT_GT(compared, kSize * kSize * 3 / 4);
    EXPECT_LE(differ, compared / 200) << differ << " of " << compared << " pixels differ from the CPU grid";
}

TEST(AlignmentPatternRender, LinesEveryFiveDegreesBelowTheThreshold) {
    const Cluster c;
    const Rendered r = render(c, 0, AlignmentPattern::Grid);
    const ChannelFrustum f = c.channel(0).frustum();
    // 15 deg circle and -5 deg meridian below 20 deg: drawn; the same meridian at 45 deg is not.
    const glm::ivec2 circle15 = centred_pixel_on(f, -30, 15, -20, 15),
                     meridian_low = centred_pixel_on(f, -5, 8, -5, 12);
    ASSERT_GE(circle15.x, 0);
    ASSERT_GE(meridian_low.x, 0);
    EXPECT_GT(brightest(r.at(circle15.x, circle15.y)), 0.5f);
    EXPECT_GT(brightest(r.at(meridian_low.x, meridian_low.y)), 0.5f);
    const glm::ivec2 meridian_high = centred_pixel_on(f, -5, 44, -5, 46);
    EXPECT_LT(brightest(r.at(meridian_high.x, meridian_high.y)), 0.02f);
    // Between the 10 and 15 deg circles: dark; between 30 and 40 the 35 deg is not a line.
    for (const glm::dvec3 d : {dome_dir(-27.5, 12.5), dome_dir(-27.5, 35.0)}) {
        const auto p = pixel_of(f, d);
        ASSERT_TRUE(p);
        EXPECT_LT(brightest(r.at(p->x, p->y)), 0.02f);
    }
    // The springline is yellow; the front meridian red.
    // (between the lines that cross them)
    const glm::ivec2 spring = centred_pixel_on(f, -29, 0, -26, 0), front = centred_pixel_on(f, 0, 42, 0, 48);
    ASSERT_GE(spring.x, 0);
    ASSERT_GE(front.x, 0);
    const glm::vec3 s = r.at(spring.x, spring.y), m = r.at(front.x, front.y);
    EXPECT_GT(s.r, 0.5f);
    EXPECT_GT(s.g, 0.7f * s.r);
    EXPECT_LT(s.b, 0.15f * s.r);
    EXPECT_GT(m.r, 0.5f);
    EXPECT_LT(m.g, 0.2f * m.r);
}

TEST(AlignmentPatternRender, LabelIsDrawnAndDiffersBetweenChannels) {
    const Cluster c;
    const Rendered a = render(c, 0, AlignmentPattern::Grid), b = render(c, 1, AlignmentPattern::Grid);
    EXPECT_EQ(a.label, "front #0");
    EXPECT_EQ(b.label, "right #1");
    // Text is white; the grid inside the label box is dimmed below 0.3 and the lines are grey or coloured.
    auto text_mask = [](const Rendered& r) {
        std::vector<bool> mask(kSize * kSize, false);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const glm::vec3 v = r.at(x, y);
                mask[y * kSize + x] = r.in_label(x, y) && std::min({v.r, v.g, v.b}) > 0.5f;
            }
        return mask;
    };
    const auto ma = text_mask(a), mb = text_mask(b);
    const long na = std::count(ma.begin(), ma.end(), true), nb = std::count(mb.begin(), mb.end(), true);
    EXPECT_GT(na, 20);
    EXPECT_GT(nb, 20);
    long differ = 0;
    for (size_t i = 0; i < ma.size(); ++i) differ += ma[i] != mb[i];
    EXPECT_GT(differ, 20);
    // The raster itself: FreeType's glyphs, different for different text.
    const TextRaster t0 = rasterize_text("front #0", 16), t1 = rasterize_text("right #1", 16);
    EXPECT_GT(t0.width, 40);
    EXPECT_GE(t0.height, 16);
    EXPECT_GT(*std::max_element(t0.coverage.begin(), t0.coverage.end()), 0.9f);
    EXPECT_NE(t0.coverage, t1.coverage);
    EXPECT_THROW(rasterize_text("x", 16, "/nonexistent/font.ttf"), std::runtime_error);
}

// Star and constellation names are UTF-8 ("Boötes"): each character is one glyph, and bytes that
// are not well-formed UTF-8 are drawn as '?', one for each byte.
TEST(TextRaster, Utf8IsDecodedAndMalformedBytesAreQuestionMarks) {
    const TextFace face(24);
    const TextRaster umlaut = face.raster("Bo\xC3\xB6tes"), plain = face.raster("Bootes");
    const TextRaster two_bytes = face.raster("Bo??tes");
    // The diaeresis over the o: same advance as the o (one glyph, not two), different pixels.
    EXPECT_EQ(umlaut.width, plain.width);
    EXPECT_NE(umlaut.coverage, plain.coverage);
    EXPECT_LT(umlaut.width, two_bytes.width);
    // Its ink lies above the o's: rows above the x-height that "Bootes" leaves empty there.
    float above = 0.0f;
    for (int y = 0; y < umlaut.height / 3; ++y)
        for (int x = 0; x < umlaut.width; ++x) above += std::max(0.0f, umlaut.at(x, y) - plain.at(x, y));
    EXPECT_GT(above, 2.0f);
    // A stray continuation byte, a lead byte cut short, an overlong '/' and a surrogate: '?' per byte.
    const std::string stray = std::string("a\x80") + "b";
    EXPECT_EQ(face.raster(stray).coverage, face.raster("a?b").coverage);
    EXPECT_EQ(face.raster("a\xC3").coverage, face.raster("a?").coverage);
    EXPECT_EQ(face.raster("\xC0\xAF").coverage, face.raster("??").coverage);
    EXPECT_EQ(face.raster("\xED\xA0\x80").coverage, face.raster("???").coverage);
    EXPECT_EQ(face.raster("tab\there").coverage, face.raster("tab?here").coverage);
}

TEST(AlignmentPatternRender, OverlapIsTintedExactlyWhereTheOtherChannelCovers) {
    const Cluster c;
    const Rendered r = render(c, 0, AlignmentPattern::Grid);
    const ChannelFrustum f = c.channel(0).frustum(), other = c.channel(1).frustum();
    const glm::vec3 tint = PatternPass::overlap_tint();
    // One direction inside the overlap, one outside, both between lines.
    const glm::dvec3 inside = dome_dir(32.5, 45), outside = dome_dir(-32.5, 45);
    ASSERT_TRUE(other.contains(inside));
    ASSERT_FALSE(other.contains(outside));
    const auto pi = pixel_of(f, inside), po = pixel_of(f, outside);
    ASSERT_TRUE(pi && po);
    EXPECT_LT(glm::length(r.at(pi->x, pi->y) - tint), 0.02f);
    EXPECT_LT(glm::length(r.at(po->x, po->y)), 0.02f);
    // Every pixel off the lines and the label, more than a pixel from the overlap's edge: tinted
    // if and only if the other channel covers its centre.
    int tinted = 0, wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (r.in_label(x, y) || brightest(cpu_grid(f, x, y)) > 0.0f) continue;
            const glm::dvec3 d = f.pixel_to_dome_direction({x + 0.5, y + 0.5});
            const auto q = other.dome_direction_to_pixel(d);
            if (q && std::abs(other.edge_distance_px(*q)) < 1.5) continue;
            const bool covered = other.contains(d);
            tinted += covered;
            wrong += glm::length(r.at(x, y) - (covered ? tint : glm::vec3(0.0f))) > 0.02f;
        }
    EXPECT_GT(tinted, 200);
    EXPECT_EQ(wrong, 0);
}

TEST(AlignmentPatternRender, WhiteAndBlackFieldsReplaceTheScene) {
    const Cluster c;
    const Rendered white = render(c, 1, AlignmentPattern::White), black = render(c, 1, AlignmentPattern::Black);
    float white_min = 1e9f, white_max = 0.0f, black_max = 0.0f;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 w = white.at(x, y), b = black.at(x, y);
            white_min = std::min({white_min, w.r, w.g, w.b});
            white_max = std::max({white_max, w.r, w.g, w.b});
            black_max = std::max({black_max, b.r, b.g, b.b});
        }
    EXPECT_NEAR(white_min, 1.0f, 1e-6f);
    EXPECT_NEAR(white_max, 1.0f, 1e-6f);
    EXPECT_EQ(black_max, 0.0f);
    // No pattern: the scene's passes run, the pattern's does not (a sky of one faint star: dark, not white).
    context();
    SceneRenderer renderer(c.cluster, c.channel(1), c.scene);
    const std::vector<std::string> names = renderer.pass_names();
    EXPECT_EQ(names.back(), "alignment pattern");
    const Image scene = renderer.render(pattern_snapshot(AlignmentPattern::Off));
    EXPECT_LT(*std::max_element(scene.rgba.begin(), scene.rgba.end()), 1.01f);
    EXPECT_NE(scene.rgba, white.image.rgba);
}

TEST(AlignmentPatternRender, OverlappingChannelsDrawTheSameLineAtTheSameDirection) {
    const Cluster c;
    const Rendered a = render(c, 0, AlignmentPattern::Grid), b = render(c, 1, AlignmentPattern::Grid);
    const ChannelFrustum fa = c.channel(0).frustum(), fb = c.channel(1).frustum();
    // Along the 30 deg meridian and the 40 deg circle in the overlap: the pixel holding each
    // point is lit in both channels (its centre is within 0.71 pixel of the line, which covers
    // it by at least half); 2.5 deg off the lines both are dark apart from the tint.
    int checked = 0;
    for (int i = 0; i <= 10; ++i) {
        for (const glm::dvec3 d : {dome_dir(30, 32 + i), dome_dir(25 + i, 40)}) {
            const auto pa = pixel_of(fa, d), pb = pixel_of(fb, d);
            if (!pa || !pb || a.in_label(pa->x, pa->y) || b.in_label(pb->x, pb->y)) continue;
            EXPECT_GT(brightest(a.at(pa->x, pa->y)), 0.3f) << "channel 0 pixel " << pa->x << "," << pa->y;
            EXPECT_GT(brightest(b.at(pb->x, pb->y)), 0.3f) << "channel 1 pixel " << pb->x << "," << pb->y;
            ++checked;
        }
        const glm::dvec3 off = dome_dir(27.5, 32.5 + 0.5 * i);
        const auto qa = pixel_of(fa, off), qb = pixel_of(fb, off);
        if (!qa || !qb) continue;
        EXPECT_LT(glm::length(a.at(qa->x, qa->y) - PatternPass::overlap_tint()), 0.02f);
        EXPECT_LT(glm::length(b.at(qb->x, qb->y) - PatternPass::overlap_tint()), 0.02f);
    }
    EXPECT_GE(checked, 15);
}
