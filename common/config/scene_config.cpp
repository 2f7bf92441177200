#include "config/scene_config.hpp"

#include <filesystem>
#include <set>
#include <stdexcept>

#include "config/cluster_config.hpp"
#include "config/config_schema.hpp"
#include "config/json_reader.hpp"
#include "atmosphere/production_quality.hpp"
#include "scene/night_sky.hpp"

namespace cupola {

namespace fs = std::filesystem;

const BodyConfig* SceneConfig::find(const std::string& name) const {
    for (const auto& b : bodies)
        if (b.name == name) return &b;
    return nullptr;
}

const std::vector<std::string>& shadow_mode_names() {
    static const std::vector<std::string> names{"exact", "fast", "lut", "illustrative", "off"};
    return names;
}

ShadowMode shadow_mode_from_name(const std::string& name) {
    const auto& n = shadow_mode_names();
    for (size_t i = 0; i < n.size(); ++i)
        if (n[i] == name) return static_cast<ShadowMode>(i);
    throw std::invalid_argument("unknown shadow mode \"" + name + "\" (exact, fast, lut, illustrative or off)");
}

namespace {

// Defaults and ranges of every field: configs/schema/scene.schema.json (JsonReader::declared_*).
// What a schema cannot say is checked here: unique body names, textures and the catalogue that
// must exist, shadow groups naming bodies of the scene that are not stars, a star without an
// atmosphere, and an atmosphere thicker than its scale heights.

ShadowGroupConfig read_shadow_group(const JsonReader& g, const SceneConfig& s) {
    auto id_of = [&](const std::string& key, const std::string& name) {
        const BodyConfig* b = s.find(name);
        if (!b) g.fail(key, "no body named \"" + name + "\" in the scene");
        if (b->kind == BodyKind::Star) g.fail(key, "\"" + name + "\" is a star: stars are light sources, not casters");
        return b->id;
    };
    ShadowGroupConfig group;
    group.parent = id_of("parent", g.string("parent"));
    const auto children = g.strings("children", {});
    if (children.empty()) g.fail("children", "a shadow group needs at least one child");
    for (const auto& name : children) {
        const uint16_t id = id_of("children", name);
        if (id == group.parent) g.fail("children", "\"" + name + "\" is the group's parent");
        group.children.push_back(id);
    }
    group.siblings_shadow_each_other = g.declared_boolean("siblings_shadow_each_other");
    g.reject_unknown_keys();
    return group;
}

ShadowConfig read_shadows(const JsonReader& r, const SceneConfig& s) {
    ShadowConfig c;
    c.mode = shadow_mode_from_name(r.declared_choice("mode"));
    c.butterworth_order = r.declared_number("butterworth_order");
    if (r.has("groups"))
        for (auto& g : r.array("groups")) c.groups.push_back(read_shadow_group(g, s));
    r.reject_unknown_keys();
    return c;
}

GlareConfig read_glare(const JsonReader& g) {
    GlareConfig c;
    c.enabled = g.declared_boolean("enabled");
    c.strength = g.declared_number("strength");
    c.extent_deg = g.declared_number("extent_deg");
    c.halo_radius_deg = g.declared_number("halo_radius_deg");
    c.halo_width_deg = g.declared_number("halo_width_deg");
    c.halo_fraction = g.declared_number("halo_fraction");
    c.streak_count = static_cast<int>(g.declared_integer("streak_count"));
    if (c.streak_count % 2 != 0)
        g.fail("streak_count", "must be even (rays twinkle in pairs so the energy stays constant)");
    c.streak_contrast = g.declared_number("streak_contrast");
    c.animation_rate = g.declared_number("animation_rate");
    c.visibility =
        g.declared_choice("visibility") == "shared" ? GlareVisibilityMode::Shared : GlareVisibilityMode::PerChannel;
    c.min_display = g.declared_number("min_display");
    c.max_sources = static_cast<int>(g.declared_integer("max_sources"));
    c.probe_size = static_cast<int>(g.declared_integer("probe_size"));
    c.halo_downsample = static_cast<int>(g.declared_integer("halo_downsample"));
    if (c.halo_downsample & (c.halo_downsample - 1)) g.fail("halo_downsample", "must be 1, 2, 4 or 8");
    g.reject_unknown_keys();
    return c;
}

// The overrides default to the preset's values.
AtmosphereConfig read_atmosphere(const JsonReader& a, const BodyConfig& body) {
    AtmosphereConfig c;
    c.present = true;
    c.preset = a.declared_choice("preset");
    c.parameters =
        c.preset == "earth" ? atmosphere::AtmosphereParameters::earth() : atmosphere::AtmosphereParameters::mars();
    c.model = a.declared_choice("model");
    atmosphere::AtmosphereParameters& p = c.parameters;
    // The ground is the body's surface; the shell keeps the preset's thickness unless overridden.
    const double thickness = a.declared_number("top_altitude_m", p.top_radius - p.bottom_radius);
    p.name = body.name;
    p.bottom_radius = body.radius_m;
    p.top_radius = body.radius_m + thickness;
    p.rayleigh_scale_height = a.declared_number("rayleigh_scale_height_m", p.rayleigh_scale_height);
    p.mie_extinction_at_550nm = a.declared_number("mie_extinction_at_550nm", p.mie_extinction_at_550nm);
    p.mie_scale_height = a.declared_number("mie_scale_height_m", p.mie_scale_height);
    p.mie_g = a.declared_number("mie_g", p.mie_g);
    if (a.has("mie_single_scattering_albedo"))
        p.mie_single_scattering_albedo =
            atmosphere::SpectralCurve::constant(a.declared_number("mie_single_scattering_albedo", 0.0));
    p.ozone_column_dobson = a.declared_number("ozone_column_dobson", p.ozone_column_dobson);
    if (a.has("ground_albedo"))
        p.ground_albedo = atmosphere::SpectralCurve::constant(a.declared_number("ground_albedo", 0.0));
    if (p.mie_scale_height >= thickness || p.rayleigh_scale_height >= thickness)
        a.fail("top_altitude_m",
               "the atmosphere (" + std::to_string(thickness) + " m) must be thicker than its scale heights");
    a.reject_unknown_keys();
    return c;
}

std::string read_texture(const JsonReader& b, const std::string& dir, const std::string& name) {
    std::string tex = b.string("texture", "generated:" + name);
    if (tex.rfind("generated:", 0) == 0) return tex;
    const std::string path = resolve_path(dir, tex);
    if (!fs::is_regular_file(path))
        b.fail("texture", "image \"" + path +
                              "\" does not exist (install it with scripts/setup.sh, or use \"generated:" + name +
                              "\")");
    return path;
}

// A required "texture": an image path, resolved against the scene's folder, that must exist.
std::string read_existing_image(const JsonReader& r, const std::string& dir) {
    const std::string path = resolve_path(dir, r.string("texture"));
    if (!fs::is_regular_file(path))
        r.fail("texture", "image \"" + path + "\" does not exist (install it with scripts/setup.sh)");
    return path;
}

RingConfig read_rings(const JsonReader& r, const std::string& dir, const BodyConfig& body) {
    RingConfig c;
    c.present = true;
    c.texture = read_existing_image(r, dir);
    c.inner_radius_m = r.declared_number("inner_radius_m");
    c.outer_radius_m = r.declared_number("outer_radius_m");
    if (c.inner_radius_m <= body.radius_m)
        r.fail("inner_radius_m", "must be larger than the planet's radius (" + std::to_string(body.radius_m) + " m)");
    if (c.outer_radius_m <= c.inner_radius_m) r.fail("outer_radius_m", "must be larger than inner_radius_m");
    c.optical_depth = r.declared_number("optical_depth");
    c.phase_albedo = r.declared_number("phase_albedo");
    if (auto t = r.optional_dvec3("tint")) c.tint = glm::vec3(*t);
    r.reject_unknown_keys();
    return c;
}

TerrainConfig read_terrain(const JsonReader& t, const std::string& dir) {
    TerrainConfig c;
    c.present = true;
    c.error_budget_px = t.declared_number("error_budget_px");
    c.segments = static_cast<int>(t.declared_integer("segments"));
    if (c.segments % 2) t.fail("segments", "must be even (a tile's parent has every other vertex)");
    if (t.has("elevation")) {
        c.elevation = resolve_path(dir, t.declared_string("elevation"));
        if (!fs::is_regular_file(c.elevation))
            t.fail("elevation", "elevation file \"" + c.elevation + "\" does not exist");
    }
    c.procedural_wavelength_m = t.declared_number("procedural_wavelength_m");
    c.procedural_amplitude_m = t.declared_number("procedural_amplitude_m");
    c.procedural_gain = t.declared_number("procedural_gain");
    c.procedural_octaves = static_cast<int>(t.declared_integer("procedural_octaves"));
    c.seed = static_cast<uint64_t>(t.declared_integer("seed"));
    c.cache_tiles = static_cast<size_t>(t.declared_integer("cache_tiles"));
    c.workers = static_cast<int>(t.declared_integer("workers"));
    t.reject_unknown_keys();
    return c;
}

BodyConfig read_body(const JsonReader& b, uint16_t id, const std::string& dir, std::set<std::string>& names) {
    BodyConfig c;
    c.id = id;
    c.name = b.declared_string("name");
    if (!names.insert(c.name).second) b.fail("name", "body name \"" + c.name + "\" is used twice");
    const std::string kind = b.declared_choice("kind");
    c.kind = kind == "star" ? BodyKind::Star : kind == "planet" ? BodyKind::Planet : BodyKind::Moon;
    c.ephemeris = b.declared_choice("ephemeris");
    c.radius_m = b.declared_number("radius_m");
    c.flattening = b.declared_number("flattening");
    if (c.flattening > 0.0 && c.kind == BodyKind::Star) b.fail("flattening", "a star is drawn as a sphere");
    c.texture = read_texture(b, dir, c.name);
    if (auto t = b.optional_dvec3("tint")) c.tint = glm::vec3(*t);
    c.albedo = b.declared_number("albedo");
    c.photometry = b.declared_choice("photometry") == "lunar-lambert" ? Photometry::LunarLambert : Photometry::Lambert;
    if (c.photometry != Photometry::Lambert && c.kind == BodyKind::Star)
        b.fail("photometry", "a star is not lit: it has no surface photometry");
    c.limb_darkening_u = b.declared_number("limb_darkening_u");
    c.radiance = b.declared_number("radiance");
    if (auto u = b.optional_dvec3("umbra_light")) {
        if (glm::any(glm::lessThan(*u, glm::dvec3(0.0))) || glm::any(glm::greaterThan(*u, glm::dvec3(1.0))))
            b.fail("umbra_light", "each component must lie in [0, 1] (light left in the umbra per unit sunlight)");
        c.umbra_light = glm::vec3(*u);
    }
    c.umbra_brightness = b.declared_number("umbra_brightness");
    c.corona = b.declared_number("corona");
    if (auto a = b.optional_child("atmosphere")) {
        if (c.kind == BodyKind::Star) a->fail("preset", "a star cannot have an atmosphere");
        c.atmosphere = read_atmosphere(*a, c);
        if (c.flattening > 0.0)
            b.fail("flattening", "a body with an atmosphere is drawn as a sphere (its air is a spherical shell)");
    }
    if (auto r = b.optional_child("rings")) {
        if (c.kind != BodyKind::Planet) r->fail("texture", "only a planet has rings");
        if (c.atmosphere.present) r->fail("texture", "a planet with an atmosphere cannot have rings yet");
        c.rings = read_rings(*r, dir, c);
    }
    if (auto t = b.optional_child("terrain")) {
        if (c.kind == BodyKind::Star) t->fail("error_budget_px", "a star has no terrain");
        if (c.flattening > 0.0) b.fail("flattening", "a body with terrain is drawn on a sphere");
        if (c.rings.present) t->fail("error_budget_px", "a planet with rings cannot have terrain yet");
        c.terrain = read_terrain(*t, dir);
    }
    b.reject_unknown_keys();
    return c;
}

MilkyWayConfig read_milky_way(const JsonReader& m, const std::string& dir) {
    MilkyWayConfig c;
    c.present = true;
    c.texture = read_existing_image(m, dir);
    c.surface_brightness = m.declared_number("surface_brightness");
    c.latitude_extent_deg = m.declared_number("latitude_extent_deg");
    m.reject_unknown_keys();
    return c;
}

OverlayStyle read_overlay_style(const JsonReader& o, OverlayKind kind) {
    OverlayStyle s = default_overlay_style(kind);
    s.visible = o.declared_boolean("visible");
    if (auto c = o.optional_dvec3("color")) s.color = *c;
    if (o.has("width_deg")) s.width_deg = o.declared_number("width_deg");
    if (o.has("text_deg")) s.text_deg = o.declared_number("text_deg");
    s.fade_s = o.declared_number("fade_s");
    o.reject_unknown_keys();
    return s;
}

OverlaysConfig read_overlays(const JsonReader& o, const std::string& dir) {
    OverlaysConfig c;
    c.present = true;
    c.figures = resolve_path(dir, o.string("figures"));
    if (!fs::is_regular_file(c.figures)) o.fail("figures", "file \"" + c.figures + "\" does not exist");
    for (size_t k = 0; k < kOverlayCount; ++k) {
        const auto kind = static_cast<OverlayKind>(k);
        const auto child = o.optional_child(overlay_names()[k]);
        c.styles[k] = child ? read_overlay_style(*child, kind) : default_overlay_style(kind);
    }
    o.reject_unknown_keys();
    return c;
}

StarFieldConfig read_stars(const JsonReader& st, const std::string& dir) {
    StarFieldConfig c;
    c.catalog = resolve_path(dir, st.string("catalog"));
    if (!fs::is_regular_file(c.catalog)) st.fail("catalog", "file \"" + c.catalog + "\" does not exist");
    c.magnitude_limit = st.declared_number("magnitude_limit");
    c.psf_sigma_arcmin = st.declared_number("psf_sigma_arcmin");
    c.zero_mag_flux = st.declared_number("zero_mag_flux");
    c.twinkle = twinkle_mode_from_name(st.declared_choice("twinkle"));
    if (st.has("sky_brightness") && st.has("bortle")) st.fail("bortle", "give sky_brightness or bortle, not both");
    if (st.has("sky_brightness")) c.sky_brightness_mag_arcsec2 = st.declared_number("sky_brightness", 0.0);
    if (st.has("bortle"))
        c.sky_brightness_mag_arcsec2 = bortle_zenith_mag_arcsec2(static_cast<int>(st.declared_integer("bortle", 0)));
    st.reject_unknown_keys();
    return c;
}

}  // namespace

OverlayStyle default_overlay_style(OverlayKind kind) {
    OverlayStyle s;
    switch (kind) {
        case OverlayKind::Constellations:
            s.color = {0.25, 0.45, 0.85};
            break;
        case OverlayKind::ConstellationNames:
            s.color = {0.35, 0.55, 0.9};
            break;
        case OverlayKind::Boundaries:
            s.color = {0.45, 0.35, 0.2}, s.width_deg = 0.06;
            break;
        case OverlayKind::GridAltAz:
            s.color = {0.2, 0.55, 0.25}, s.width_deg = 0.06;
            break;
        case OverlayKind::GridEquatorial:
            s.color = {0.2, 0.35, 0.7}, s.width_deg = 0.06;
            break;
        case OverlayKind::GridEcliptic:
            s.color = {0.7, 0.55, 0.15}, s.width_deg = 0.06;
            break;
        case OverlayKind::Horizon:
            s.color = {0.8, 0.5, 0.25}, s.width_deg = 0.15;
            break;
        case OverlayKind::Meridian:
            s.color = {0.6, 0.6, 0.6};
            break;
        case OverlayKind::Cardinals:
            s.color = {0.95, 0.6, 0.3}, s.text_deg = 3.0;
            break;
        case OverlayKind::Labels:
            s.color = {0.8, 0.8, 0.75}, s.text_deg = 1.2;
            break;
    }
    return s;
}

SceneConfig load_scene_config(const std::string& file) {
    SceneConfig s;
    s.file = file;
    const std::string dir = fs::absolute(file).parent_path().string();
    const nlohmann::json doc = JsonReader::parse_file(file);
    JsonReader r(doc, file, &config_schema("scene"));

    auto bodies = r.array("bodies");
    if (bodies.empty()) r.fail("bodies", "at least one body is required");
    if (bodies.size() > 1000) r.fail("bodies", "at most 1000 bodies");
    std::set<std::string> names;
    for (auto& b : bodies) s.bodies.push_back(read_body(b, static_cast<uint16_t>(s.bodies.size()), dir, names));
    s.stars = read_stars(r.child("stars"), dir);
    s.shadows = read_shadows(r.section("shadows"), s);
    if (auto g = r.optional_child("glare")) s.glare = read_glare(*g);
    if (auto m = r.optional_child("milky_way")) s.milky_way = read_milky_way(*m, dir);
    if (auto o = r.optional_child("overlays")) s.overlays = read_overlays(*o, dir);
    r.reject_unknown_keys();
    return s;
}

}  // namespace cupola
