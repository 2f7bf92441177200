// The presenter's overlays (common/overlay, slave/passes/overlay_pass): the constellation data
// against the star catalogue, the reader's errors, the names the control channel takes, the fades,
// the observer's frame, and real renders on headless EGL: Orion's lines through their stars'
// catalogue positions, a line and a label that cross the edge between two channels continuous in
// the stitched 2048 x 2048 domemaster, and a line as wide in dome degrees on channels of
// different resolutions.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/rotate_vector.hpp>
#include <map>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "control/control_command.hpp"
#include "dome/domemaster_stitcher.hpp"
#include "image/frame_image.hpp"
#include "overlay/arc_chunks.hpp"
#include "overlay/constellation_figures.hpp"
#include "overlay/label_declutter.hpp"
#include "overlay/overlay_frames.hpp"
#include "overlay/overlay_lines.hpp"
#include "overlay_fader.hpp"
#include "passes/overlay_pass.hpp"
#include "projection/fisheye.hpp"
#include "scene/star_catalog.hpp"
#include "scene_renderer.hpp"
#include "support/headless_gl.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

const std::string kFigures = test::source_path("data/sky/constellations.json");

double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
    return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

// The catalogue star a direction is on (within 1 arcminute), or "".
std::string star_at(const std::vector<Star>& stars, const glm::dvec3& d) {
    for (const Star& s : stars)
        if (angle_deg(s.direction(), d) < 1.0 / 60.0) return s.name;
    return "";
}

const ConstellationFigure& find_figure(const std::vector<ConstellationFigure>& f, const std::string& id) {
    for (const auto& c : f)
        if (c.id == id) return c;
    throw std::runtime_error("no figure " + id);
}

// Whether two catalogue stars are joined by a segment of the figure.
bool joined(const ConstellationFigure& f, const std::vector<Star>& stars, const std::string& a, const std::string& b) {
    for (const auto& line : f.lines)
        for (size_t i = 1; i < line.size(); ++i) {
            const std::string p = star_at(stars, line[i - 1]), q = star_at(stars, line[i]);
            if ((p == a && q == b) || (p == b && q == a)) return true;
        }
    return false;
}

}  // namespace

TEST(OverlayData, EightyEightFiguresAndOrionJoinsItsStarsAtTheirCataloguePositions) {
    const auto figures = load_constellation_figures(kFigures);
    EXPECT_EQ(figures.size(), 88u);
    const auto stars = load_star_catalog(test::source_path("data/stars/bright_stars.csv"), 6.5);
    const ConstellationFigure& ori = find_figure(figures, "Ori");
    EXPECT_EQ(ori.name, "Orion");
    size_t vertices = 0, on_stars = 0;
    for (const auto& line : ori.lines)
        for (const auto& p : line) {
            ++vertices;
            on_stars += std::any_of(stars.begin(), stars.end(),
                                    [&](const Star& st) { return angle_deg(st.direction(), p) < 1.0 / 60.0; })
                            ? 1
                            : 0;
        }
    EXPECT_EQ(on_stars, vertices) << "every vertex of Orion's figure is a catalogue star";
    // The shoulders, the belt, the knees (Rigel and Saiph) and the belt's links.
    EXPECT_TRUE(joined(ori, stars, "Betelgeuse", "Bellatrix"));
    EXPECT_TRUE(joined(ori, stars, "Alnitak", "Alnilam"));
    EXPECT_TRUE(joined(ori, stars, "Alnilam", "Mintaka"));
    EXPECT_TRUE(joined(ori, stars, "Alnitak", "Saiph"));
    EXPECT_TRUE(joined(ori, stars, "Betelgeuse", "Alnitak"));
    EXPECT_FALSE(joined(ori, stars, "Betelgeuse", "Rigel")) << "opposite corners are not joined";
    EXPECT_FALSE(ori.boundaries.empty());
    const auto lines = overlay_lines(figures);
    for (const SkyArc& a : lines[static_cast<size_t>(OverlayKind::Constellations)])
        ASSERT_LT(angle_deg(a.a, a.b), 2.0001) << "arcs of at most two degrees";
}

// The runs the pass culls: none that holds an arc end inside a channel is ever culled, and most of
// a whole-sky grid is, for a 60 degree channel.
TEST(OverlayData, CullingKeepsEveryRunThatCanTouchTheChannel) {
    const auto lines = overlay_lines(load_constellation_figures(kFigures));
    const auto& grid = lines[static_cast<size_t>(OverlayKind::GridEquatorial)];
    const auto chunks = arc_chunks(grid, 16);
    const ChannelFrustum f(EulerDeg{20.0, 35.0, 5.0}, FovDeg{30.0, 30.0, 30.0, 30.0}, 64, 64);
    const glm::dvec4 t(f.tan_left(), f.tan_right(), f.tan_down(), f.tan_up());
    const glm::dmat3 to_channel = glm::transpose(f.rotation());
    size_t kept = 0;
    for (const ArcChunk& c : chunks) {
        const bool touches = cone_touches_frustum(to_channel * c.centre, c.radius_rad, t);
        kept += touches ? 1 : 0;
        for (int i = c.first_arc; i < c.first_arc + c.arc_count; ++i) {
            if (f.contains(grid[i].a) || f.contains(grid[i].b)) {
                ASSERT_TRUE(touches) << "arc " << i;
            }
        }
    }
    std::printf("equatorial grid: %zu of %zu runs kept for a 60 degree channel\n", kept, chunks.size());
    EXPECT_LT(kept, chunks.size() / 4);
    // Arc by arc, as the pass culls within the runs it keeps: no arc with an end inside is culled.
    const FrustumSides sides(t);
    size_t arcs_kept = 0;
    for (const SkyArc& a : grid) {
        const glm::dvec4 cone = arc_cone(a);
        const bool touches = sides.touched_by(to_channel * glm::dvec3(cone), cone.w);
        if (f.contains(a.a) || f.contains(a.b)) ASSERT_TRUE(touches);
        arcs_kept += touches ? 1 : 0;
    }
    std::printf("equatorial grid: %zu of %zu arcs kept\n", arcs_kept, grid.size());
    EXPECT_LT(arcs_kept, kept * 16 * 2 / 3) << "fewer than the runs hold";
}

// Every point of every overlay's arcs, along its own circle, lies within the arc's cone.
TEST(OverlayData, EveryArcLiesWithinItsCone) {
    const auto lines = overlay_lines(load_constellation_figures(kFigures));
    double worst_margin_deg = 1e9;
    for (const auto& arcs : lines)
        for (const SkyArc& arc : arcs) {
            const glm::dvec4 cone = arc_cone(arc);
            // The arc is a turned about its pole from 0 to phi.
            const glm::dvec3 ap = arc.a - glm::dot(arc.a, arc.pole) * arc.pole;
            const glm::dvec3 bp = arc.b - glm::dot(arc.b, arc.pole) * arc.pole;
            const double phi = std::atan2(glm::dot(glm::cross(ap, bp), arc.pole), glm::dot(ap, bp));
            for (int i = 0; i <= 16; ++i) {
                const glm::dvec3 p = glm::rotate(arc.a, phi * i / 16.0, arc.pole);
                const double off = angle_deg(glm::dvec3(cone), p);
                worst_margin_deg = std::min(worst_margin_deg, glm::degrees(cone.w) - off);
                ASSERT_LE(off, glm::degrees(cone.w) + 1e-9)
                    << "point " << i << " of an arc at latitude " << arc.lat_rad;
            }
        }
    std::printf("arc cones: the closest point lies %.5f degrees inside its cone\n", worst_margin_deg);
}

// Labels that overlap on the sky: the one of higher priority stays, equal priorities go in order;
// labels clear of each other all stay, and a label not taking part (its overlay hidden) hides none.
TEST(OverlayLabels, OfTwoOverlappingLabelsTheHigherPriorityIsDrawn) {
    const double deg = glm::radians(1.0);
    const glm::dvec3 up(0.0, 0.0, 1.0);
    const auto at = [&](double ra_deg, double dec_deg) { return radec_deg_to_dir(ra_deg, dec_deg); };
    const glm::dvec4 wide(0.0, -0.25 * deg, 3.0 * deg, 0.25 * deg);  // 3 x 0.5 degrees, to the right
    std::vector<LabelFootprint> labels = {
        {at(100.0, 20.0), wide, kConstellationPriority},  // 0: overlaps 1 (1 degree to its right)
        {at(101.0, 20.0), wide, kStarPriority},           // 1: drawn first
        {at(100.0, 20.6), wide, kConstellationPriority},  // 2: 0.6 degrees above 0: clear of it
        {at(100.5, 20.6), wide, kConstellationPriority},  // 3: overlaps 2, after it
        {at(140.0, 20.0), wide, kConstellationPriority},  // 4: far away
    };
    std::vector<bool> kept = declutter_labels(labels, up);
    EXPECT_EQ(kept, (std::vector<bool>{false, true, true, false, true}));
    labels.erase(labels.begin() + 1);  // the star's overlay hidden: the constellation's name stays
    kept = declutter_labels(labels, up);
    EXPECT_EQ(kept, (std::vector<bool>{true, true, false, true}));
    // Boxes are in angle: a label 3.1 degrees to the right of another (beyond its 3 degree box) is
    // clear of it at any declination where the text stands upright.
    for (double dec : {0.0, 45.0, 80.0}) {
        const double step = 3.1 / std::cos(glm::radians(dec));
        const std::vector<LabelFootprint> row = {{at(100.0, dec), wide, 0}, {at(100.0 - step, dec), wide, 1}};
        EXPECT_EQ(declutter_labels(row, up), (std::vector<bool>{true, true})) << dec;
    }
}

TEST(OverlayData, MalformedFiguresAreRefusedNamingTheField) {
    const auto error = [](const std::string& text) {
        try {
            parse_constellation_figures(text, "bad.json");
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string head =
        R"({"boundaries": [], "constellations": [{"id": "X", "name": "X", "rank": 1, "labels": [{"text": "X", "ra_deg": 1, "dec_deg": 2}], "lines": )";
    EXPECT_NE(error(head + "[[[1, 2], [400, 3]]]}]}").find("constellations[0].lines[0][1][0]: right ascension"),
              std::string::npos)
        << error(head + "[[[1, 2], [400, 3]]]}]}");
    EXPECT_NE(error(head + "[[[1, 2]]]}]}").find("constellations[0].lines[0]: has 1 entries"), std::string::npos);
    EXPECT_NE(error(head + "[[[1, 2], [3, 95]]]}]}").find("declination"), std::string::npos);
    EXPECT_NE(error("{\"constellations\": [").find("bad.json: is not JSON"), std::string::npos);
    // A number too large for a double (found by cupola-fuzz-sky-figures): refused, not thrown past.
    EXPECT_NE(error(head + "[[[1, -61E3323], [3, 4]]]}]}").find("is not JSON"), std::string::npos);
    EXPECT_NE(error(R"({"constellations": [], "boundaries": []})").find("at least 1"), std::string::npos);
    EXPECT_NE(error(head + R"([]}], "boundaries": [{"id": "Y", "polygons": []}]})").find("\"Y\" is not one of"),
              std::string::npos);
    EXPECT_THROW(load_constellation_figures("/nonexistent/figures.json"), std::runtime_error);
}

TEST(OverlayControl, NamesShowHideAndTheShowsEvents) {
    EXPECT_EQ(overlay_from_name("grid equatorial"), OverlayKind::GridEquatorial);
    EXPECT_EQ(overlay_from_name("constellation_names"), OverlayKind::ConstellationNames);
    EXPECT_THROW(overlay_from_name("grid galactic"), std::invalid_argument);
    ControlCommand c = parse_control_line("show grid equatorial");
    EXPECT_EQ(c.verb, ControlVerb::Overlay);
    EXPECT_EQ(*c.overlay, static_cast<size_t>(OverlayKind::GridEquatorial));
    EXPECT_TRUE(*c.overlay_shown);
    c = parse_control_line("hide constellations");
    EXPECT_FALSE(*c.overlay_shown);
    EXPECT_FALSE(parse_control_line("show overlays show").overlay);
    EXPECT_NE(control_help().find("show|hide <overlay>"), std::string::npos) << control_help();
    try {
        parse_control_line("show grid galactic");
        FAIL();
    } catch (const ControlError& e) {
        EXPECT_NE(std::string(e.what()).find("not an overlay"), std::string::npos) << e.what();
    }
}

TEST(OverlayFades, TheMasterFadesEachOverlayLinearlyOverItsFadeTime) {
    SceneConfig scene;
    scene.overlays.present = true;
    scene.overlays.styles[0].fade_s = 2.0;  // constellations
    scene.overlays.styles[3].fade_s = 0.0;  // the alt-az grid switches at once
    scene.overlays.styles[3].visible = true;
    ShowSettings settings;
    EXPECT_TRUE(overlay_targets(settings, scene)[3]);
    EXPECT_FALSE(overlay_targets(settings, scene)[0]);
    OverlayFader fader(scene);
    auto a = fader.step(overlay_targets(settings, scene), 0.5);
    EXPECT_EQ(a[0], 0.0f);
    EXPECT_EQ(a[3], 1.0f);
    settings.overlays[0] = true;
    settings.overlays[3] = false;
    for (float want : {0.25f, 0.5f, 0.75f, 1.0f, 1.0f}) {
        a = fader.step(overlay_targets(settings, scene), 0.5);
        EXPECT_FLOAT_EQ(a[0], want);
        EXPECT_EQ(a[3], 0.0f);
    }
    scene.overlays.present = false;  // a scene without overlays shows none whatever the show says
    EXPECT_FALSE(overlay_targets(settings, scene)[0]);
}

TEST(OverlayFrames, TheObserversHorizonFrameFromTheGroundUnderTheCamera) {
    const SceneConfig scene = load_scene_config(test::source_path("configs/scenes/earth-moon.json"));
    const uint16_t earth = scene.find("earth")->id;
    Snapshot s;
    for (const auto& b : scene.bodies) s.bodies.push_back({b.id, glm::dvec3(1e13 * (b.id + 1), 0.0, 0.0)});
    s.bodies[earth].position_m = glm::dvec3(0.0);  // its pole along world z: orientation identity
    const double lat = glm::radians(40.0);
    s.camera_position_m = 6.371e6 * glm::dvec3(std::cos(lat), 0.0, std::sin(lat));
    const OverlayFrames f = overlay_frames(s, scene);
    ASSERT_TRUE(f.horizon);
    EXPECT_EQ(*f.ground_body, earth);
    const glm::dmat3 h = *f.horizon;
    EXPECT_NEAR(glm::length(h[2] - glm::normalize(s.camera_position_m)), 0.0, 1e-12);  // zenith
    EXPECT_NEAR(angle_deg(h[0], glm::dvec3(0.0, 0.0, 1.0)), 40.0, 1e-9);  // the pole: 40 degrees above north
    EXPECT_NEAR(glm::dot(glm::cross(h[0], h[1]), h[2]), 1.0, 1e-12);      // right-handed
    EXPECT_NEAR(angle_deg(h[1], glm::dvec3(0.0, -1.0, 0.0)), 0.0, 1e-9);  // west
    s.camera_position_m *= 3.0;                                           // two radii up: no ground, no horizon
    EXPECT_FALSE(overlay_frames(s, scene).horizon);
    EXPECT_NEAR(angle_deg(overlay_frames(s, scene).ecliptic[2], glm::dvec3(0.0, 0.0, 1.0)), 23.4392794, 1e-6);
}

// ---- Renders ----

namespace {

// A scene with only what the overlays need: the Sun and the Earth far behind the camera, the
// bright-star catalogue (stars hidden by the snapshot's limit), and the overlays from `figures`.
SceneConfig overlay_scene(const std::string& tag, const std::string& figures, const std::string& styles) {
    const std::string dir = test::scratch_dir("overlays_" + tag);
    test::write_text(dir + "/scene.json", R"({ "bodies": [
        { "name": "sun", "kind": "star", "ephemeris": "sun", "radius_m": 6.957e8, "radiance": 5.8e4 },
        { "name": "earth", "kind": "planet", "ephemeris": "earth", "radius_m": 6.371e6 } ],
      "stars": { "catalog": ")" + test::source_path("data/stars/bright_stars.csv") +
                                              R"(" },
      "overlays": { "figures": ")" + figures + "\", " +
                                              styles + " } }");
    return load_scene_config(dir + "/scene.json");
}

ClusterConfig channels(const std::vector<std::pair<EulerDeg, int>>& list, double fov_deg) {
    ClusterConfig c;
    for (const auto& [orientation, size] : list) {
        ChannelConfig ch;
        ch.id = static_cast<int>(c.channels.size());
        ch.name = "c" + std::to_string(ch.id);
        ch.width = ch.height = size;
        ch.orientation = orientation;
        ch.fov = {fov_deg / 2, fov_deg / 2, fov_deg / 2, fov_deg / 2};
        c.channels.push_back(ch);
    }
    return c;
}

// Camera at the origin looking along `forward` with `up` (world), the bodies far behind it, the
// overlays of `shown` fully in, exposure 1, no stars.
Snapshot overlay_snapshot(const glm::dvec3& forward, const glm::dvec3& up, std::initializer_list<OverlayKind> shown) {
    Snapshot s;
    s.bodies = {{0, -1.5e11 * forward}, {1, -1.6e11 * forward}};
    const glm::dvec3 f = glm::normalize(forward), r = glm::normalize(glm::cross(f, up));
    s.camera_orientation = glm::quat_cast(glm::dmat3(r, glm::cross(r, f), -f));
    s.settings.exposure = 1.0f;
    s.settings.star_magnitude_limit = -30.0f;
    for (OverlayKind k : shown) s.settings.overlay_alpha[static_cast<size_t>(k)] = 1.0f;
    return s;
}

double lum(const Image& img, int x, int y) {
    const float* p = img.pixel(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// The pixel (x right, y down) of a world direction in channel ch of a cluster, for a snapshot.
std::optional<glm::dvec2> pixel_of(const ChannelFrustum& f, const Snapshot& s, const glm::dvec3& world) {
    const glm::dvec3 dome = glm::transpose(glm::mat3_cast(s.camera_orientation)) * world;
    return f.dome_direction_to_pixel(dome);
}

}  // namespace

TEST(OverlayRender, OrionsLinesRunThroughItsStarsCataloguePositions) {
    const SceneConfig scene =
        overlay_scene("orion", kFigures, R"("constellations": { "color": [1, 1, 1], "width_deg": 0.3, "fade_s": 0 })");
    const ClusterConfig cluster = channels({{{0, 0, 0}, 256}}, 50.0);
    test::headless_gl();
    SceneRenderer r(cluster, cluster.channels[0], scene);
    ASSERT_NE(r.overlays(), nullptr);
    EXPECT_GT(r.overlays()->arc_count(OverlayKind::Constellations), 1000u);
    const Snapshot s =
        overlay_snapshot(radec_deg_to_dir(83.8, -1.0), glm::dvec3(0, 0, 1), {OverlayKind::Constellations});
    const Image img = r.render(s);
    const ChannelFrustum f = cluster.channels[0].frustum();
    const auto stars = load_star_catalog(test::source_path("data/stars/bright_stars.csv"), 3.0);
    int lit = 0, dark = 0, checked = 0;
    for (const char* name : {"Betelgeuse", "Rigel", "Bellatrix", "Saiph", "Alnitak", "Alnilam", "Mintaka"}) {
        const auto it = std::find_if(stars.begin(), stars.end(), [&](const Star& st) { return st.name == name; });
        ASSERT_NE(it, stars.end()) << name;
        const auto p = pixel_of(f, s, it->direction());
        ASSERT_TRUE(p) << name;
        ++checked;
        lit += lum(img, static_cast<int>(p->x), static_cast<int>(p->y)) > 0.5 ? 1 : 0;
    }
    EXPECT_EQ(lit, checked) << "every star of the figure is on a drawn line";
    // Between Betelgeuse and Rigel (not joined) the middle of the figure stays dark: 2 degrees
    // west of the belt's middle.
    const auto mid = pixel_of(f, s, radec_deg_to_dir(81.5, -4.0));
    ASSERT_TRUE(mid);
    dark = lum(img, static_cast<int>(mid->x), static_cast<int>(mid->y)) < 0.02 ? 1 : 0;
    EXPECT_EQ(dark, 1);
    // Hidden: nothing drawn at all.
    Snapshot off = s;
    off.settings.overlay_alpha = {};
    const Image none = r.render(off);
    double sum = 0.0;
    for (int y = 0; y < none.height; ++y)
        for (int x = 0; x < none.width; ++x) sum += lum(none, x, y);
    EXPECT_EQ(sum, 0.0);
}

namespace {

// A figures file of one constellation: a line from a to b and a label at `label` (world
// directions; RA/Dec in degrees in the file).
std::string one_line_figures(const std::string& tag, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& label) {
    const auto radec = [](const glm::dvec3& d) {
        double ra = glm::degrees(std::atan2(d.y, d.x));
        if (ra < 0.0) ra += 360.0;
        char buf[80];
        std::snprintf(buf, sizeof buf, "%.9f, %.9f", ra, glm::degrees(std::asin(std::clamp(d.z, -1.0, 1.0))));
        return std::string(buf);
    };
    const std::string file = test::scratch_dir("overlay_figures_" + tag) + "/figures.json";
    test::write_text(file, R"({"boundaries": [], "constellations": [{"id": "Tst", "name": "Edge Label", "rank": 1,
        "labels": [{"text": "Edge Label", "ra_deg": )" +
                               radec(label).replace(radec(label).find(','), 1, ", \"dec_deg\":") +
                               R"(}], "lines": [[[)" + radec(a) + "], [" + radec(b) + "]]]}]}");
    return file;
}

// The line's centre across it, at a point p of the domemaster (pixels) with unit normal n: the
// luminance-weighted mean offset over +-8 px.
double centre_offset_px(const Image& dome, glm::dvec2 p, glm::dvec2 n) {
    double sum = 0.0, moment = 0.0;
    for (double t = -8.0; t <= 8.0; t += 0.25) {
        float px[4];
        sample_bilinear(dome, p.x + t * n.x, p.y + t * n.y, px);
        const double l = 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
        sum += l;
        moment += l * t;
    }
    return sum > 0.0 ? moment / sum : 1e9;
}

}  // namespace

TEST(OverlayRender, ALineAndALabelAcrossAChannelEdgeAreContinuousInTheDomemaster) {
    // Two channels 512 x 512, 40 degrees wide, 36 degrees apart (4 degrees of overlap), 30 up.
    const ClusterConfig cluster = channels({{{0, 30, 0}, 512}, {{36, 30, 0}, 512}}, 40.0);
    const ChannelFrustum fa = cluster.channels[0].frustum(), fb = cluster.channels[1].frustum();
    // The dome frame is the world frame here (camera orientation identity, no tilt).
    const glm::dvec3 ca = fa.pixel_to_dome_direction({256, 300}), cb = fb.pixel_to_dome_direction({256, 200});
    const glm::dvec3 mid = glm::normalize(ca + cb), up = glm::normalize(glm::cross(glm::cross(ca, cb), mid));
    const glm::dvec3 label = glm::normalize(mid + 0.08 * up);  // about 4.6 degrees above the line
    const SceneConfig scene = overlay_scene("edge", one_line_figures("edge", ca, cb, label),
                                            R"("constellations": { "color": [1, 1, 1], "width_deg": 0.2, "fade_s": 0 },
           "constellation_names": { "color": [1, 1, 1], "text_deg": 2.5, "fade_s": 0 })");
    // The line and the label in frames of their own (the label's text runs across the line).
    Snapshot s = overlay_snapshot(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), {OverlayKind::Constellations});
    s.camera_orientation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    s.bodies = {{0, glm::dvec3(0.0, -1.5e11, 0.0)}, {1, glm::dvec3(0.0, -1.6e11, 0.0)}};  // below the dome
    Snapshot text = s;
    text.settings.overlay_alpha = {};
    text.settings.overlay_alpha[static_cast<size_t>(OverlayKind::ConstellationNames)] = 1.0f;
    test::headless_gl();
    std::vector<Image> images, labels;
    for (const auto& ch : cluster.channels) {
        SceneRenderer r(cluster, ch, scene);
        images.push_back(r.render(s));
        labels.push_back(r.render(text));
    }
    const DomeConfig dome;
    const int size = 2048;
    const Image master = stitch_domemaster(dome, {fa, fb}, {&images[0], &images[1]}, size);
    const FisheyeMapping fish(dome.fov_deg);
    // Along the line, every 0.1 degree: its drawn centre against where the circle is.
    const glm::dvec3 pole = glm::normalize(glm::cross(ca, cb));
    const double length = angle_deg(ca, cb);
    double worst = 0.0;
    int samples = 0, in_both = 0;
    for (double t = 2.0; t < length - 2.0; t += 0.1) {
        const glm::dvec3 d =
            glm::normalize(std::cos(glm::radians(t)) * ca + std::sin(glm::radians(t)) * glm::cross(pole, ca));
        const glm::dvec3 d2 = glm::normalize(d + 1e-4 * pole);
        const glm::dvec2 p = FisheyeMapping::uv_to_pixel(*fish.direction_to_uv(d), size);
        const glm::dvec2 n = glm::normalize(FisheyeMapping::uv_to_pixel(*fish.direction_to_uv(d2), size) - p);
        const double e = centre_offset_px(master, p, n);
        worst = std::max(worst, std::abs(e));
        ++samples;
        in_both += fa.contains(d) && fb.contains(d) ? 1 : 0;
    }
    std::printf("line across the edge: %d points, %d in both channels, worst centre off by %.3f px\n", samples, in_both,
                worst);
    EXPECT_GT(in_both, 10);
    EXPECT_LT(worst, 0.5);
    // The label: each channel remapped alone; where both cover, its ink is in the same place.
    const Image ra = remap_channel_to_fisheye(dome, fa, labels[0], size),
                rb = remap_channel_to_fisheye(dome, fb, labels[1], size);
    glm::dvec2 ink_a(0.0), ink_b(0.0);
    double sum_a = 0.0, sum_b = 0.0;
    const glm::dvec2 lp = FisheyeMapping::uv_to_pixel(*fish.direction_to_uv(label), size);
    for (int y = static_cast<int>(lp.y) - 80; y < lp.y + 80; ++y)
        for (int x = static_cast<int>(lp.x) - 200; x < lp.x + 200; ++x) {
            if (ra.pixel(x, y)[3] < 1.0f || rb.pixel(x, y)[3] < 1.0f) continue;  // not in both
            const double a = lum(ra, x, y), b = lum(rb, x, y);
            ink_a += a * glm::dvec2(x, y), ink_b += b * glm::dvec2(x, y);
            sum_a += a, sum_b += b;
        }
    ASSERT_GT(sum_a, 20.0) << "the label crosses the overlap";
    std::printf("label in the overlap: ink %.1f and %.1f, centres %.3f px apart\n", sum_a, sum_b,
                glm::length(ink_a / sum_a - ink_b / sum_b));
    EXPECT_NEAR(sum_b / sum_a, 1.0, 0.05);
    EXPECT_LT(glm::length(ink_a / sum_a - ink_b / sum_b), 0.5);
}

TEST(OverlayRender, ALineIsAsWideInDomeDegreesAtEveryResolution) {
    // The line runs down the middle of the first two channels and across the last two (rolled 45
    // degrees) diagonally, where the anti-aliasing ramp is widest (fwidth is |ds/dx| + |ds/dy|).
    const ClusterConfig cluster =
        channels({{{0, 0, 0}, 512}, {{0, 0, 0}, 160}, {{0, 0, 45}, 512}, {{0, 0, 45}, 160}}, 40.0);
    const ChannelFrustum f = cluster.channels[0].frustum();
    // A line down the middle of the channels.
    const glm::dvec3 top = f.pixel_to_dome_direction({256, 0}), bottom = f.pixel_to_dome_direction({256, 512});
    const SceneConfig scene =
        overlay_scene("width", one_line_figures("width", top, bottom, glm::dvec3(1, 0, 0)),
                      R"("constellations": { "color": [1, 1, 1], "width_deg": 0.4, "fade_s": 0 })");
    Snapshot s = overlay_snapshot(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), {OverlayKind::Constellations});
    s.camera_orientation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    s.bodies = {{0, glm::dvec3(0.0, 0.0, 1.5e11)}, {1, glm::dvec3(0.0, 0.0, 1.6e11)}};  // behind the camera
    test::headless_gl();
    for (const auto& ch : cluster.channels) {
        const Image img = SceneRenderer(cluster, ch, scene).render(s);
        const ChannelFrustum fc = ch.frustum();
        // Across a row the line is its width wide, or sqrt(2) times that diagonally (rows near the
        // centre only, where a pixel spans the same angle either way).
        const bool diagonal = ch.orientation.roll_deg != 0.0;
        const int y0 = diagonal ? 2 * img.height / 5 : img.height / 4, y1 = img.height - y0;
        double width = 0.0;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < img.width; ++x)
                width += lum(img, x, y) * angle_deg(fc.pixel_to_dome_direction({x, y + 0.5}),
                                                    fc.pixel_to_dome_direction({x + 1.0, y + 0.5}));
        width /= (y1 - y0) * (diagonal ? std::sqrt(2.0) : 1.0);
        std::printf("%d px channel (%.3f deg a pixel), %s: the line is %.4f deg wide (asked 0.4)\n", ch.width,
                    40.0 / ch.width, diagonal ? "diagonal" : "vertical", width);
        EXPECT_NEAR(width, 0.4, diagonal ? 0.004 : 0.012) << ch.width << " px";
    }
}

// The real sky around Gemini with the constellations' names and the stars' and bodies' labels, on
// two channels whose edge runs through it: both draw the same labels, and some names that would
// overlap others are dropped.
TEST(OverlayRender, BothChannelsDrawTheSameLabelsAndDropTheOverlappingOnes) {
    const SceneConfig scene =
        overlay_scene("declutter", kFigures, R"("constellation_names": { "fade_s": 0 }, "labels": { "fade_s": 0 })");
    const ClusterConfig cluster = channels({{{-12.0, 0.0, 0.0}, 128}, {{12.0, 0.0, 0.0}, 128}}, 40.0);
    test::headless_gl();
    SceneRenderer left(cluster, cluster.channels[0], scene), right(cluster, cluster.channels[1], scene);
    const Snapshot s = overlay_snapshot(radec_deg_to_dir(112.0, 25.0), glm::dvec3(0, 0, 1),
                                        {OverlayKind::ConstellationNames, OverlayKind::Labels});
    left.render(s);
    right.render(s);
    const auto& drawn = left.overlays()->labels_drawn();
    EXPECT_EQ(drawn, right.overlays()->labels_drawn());
    const auto& labels = left.overlays()->labels();
    int shown = 0, dropped = 0;
    std::string dropped_names;
    for (size_t i = 0; i < labels.size(); ++i) {
        if (labels[i].kind != OverlayKind::ConstellationNames && labels[i].kind != OverlayKind::Labels) continue;
        if (labels[i].body) continue;  // the bodies are far behind the camera
        ++shown;
        if (!drawn[i]) ++dropped, dropped_names += " " + labels[i].text;
    }
    std::printf("labels: %d of %d dropped:%s\n", dropped, shown, dropped_names.c_str());
    EXPECT_GT(dropped, 0);
    EXPECT_LT(dropped, shown / 4);
}
