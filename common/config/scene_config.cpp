#include "config/scene_config.hpp"

#include <filesystem>
#include <set>
#include <stdexcept>

#include "config/cluster_config.hpp"
#include "config/json_reader.hpp"
#include "atmosphere/production_quality.hpp"

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
ShadowConfig read_shadows(const JsonReader& r, const SceneConfig& s) {
    ShadowConfig c;
    c.mode = shadow_mode_from_name(r.one_of("mode", shadow_mode_names(), "exact"));
    c.butterworth_order = r.number_in("butterworth_order", 0.5, 64.0, c.butterworth_order);
    auto id_of = [&](const JsonReader& g, const std::string& key, const std::string& name) {
        const BodyConfig* b = s.find(name);
        if (!b) g.fail(key, "no body named \"" + name + "\" in the scene");
        if (b->kind == BodyKind::Star) g.fail(key, "\"" + name + "\" is a star: stars are light sources, not casters");
        return b->id;
    };
    if (r.has("groups")) {
        for (auto& g : r.array("groups")) {
            ShadowGroupConfig group;
            group.parent = id_of(g, "parent", g.string("parent"));
            const auto children = g.strings("children", {});
            if (children.empty()) g.fail("children", "a shadow group needs at least one child");
            for (const auto& name : children) {
                const uint16_t id = id_of(g, "children", name);
                if (id == group.parent) g.fail("children", "\"" + name + "\" is the group's parent");
                group.children.push_back(id);
            }
            group.siblings_shadow_each_other = g.boolean("siblings_shadow_each_other", false);
            g.reject_unknown_keys();
            c.groups.push_back(group);
        }
    }
    r.reject_unknown_keys();
    return c;
}

GlareConfig read_glare(const JsonReader& g) {
    GlareConfig c;
    c.enabled = g.boolean("enabled", true);
    c.strength = g.number_in("strength", 0.0, 1e6, c.strength);
    c.extent_deg = g.number_in("extent_deg", 1.0, 85.0, c.extent_deg);
    c.halo_radius_deg = g.number_in("halo_radius_deg", 0.1, 30.0, c.halo_radius_deg);
    c.halo_width_deg = g.number_in("halo_width_deg", 0.01, 10.0, c.halo_width_deg);
    c.halo_fraction = g.number_in("halo_fraction", 0.0, 1.0, c.halo_fraction);
    c.streak_count = static_cast<int>(g.integer_in("streak_count", 2, 1024, c.streak_count));
    if (c.streak_count % 2 != 0)
        g.fail("streak_count", "must be even (rays twinkle in pairs so the energy stays constant)");
    c.streak_contrast = g.number_in("streak_contrast", 0.0, 1.0, c.streak_contrast);
    c.animation_rate = g.number_in("animation_rate", 0.0, 100.0, c.animation_rate);
    c.visibility = g.one_of("visibility", {"shared", "per_channel"}, "shared") == "shared"
                       ? GlareVisibilityMode::Shared
                       : GlareVisibilityMode::PerChannel;
    c.min_display = g.number_in("min_display", 0.0, 1e6, c.min_display);
    c.max_sources = static_cast<int>(g.integer_in("max_sources", 1, 64, c.max_sources));
    c.probe_size = static_cast<int>(g.integer_in("probe_size", 8, 512, c.probe_size));
    g.reject_unknown_keys();
    return c;
}

AtmosphereConfig read_atmosphere(const JsonReader& a, const BodyConfig& body) {
    AtmosphereConfig c;
    c.present = true;
    c.preset = a.one_of("preset", {"earth", "mars"});
    c.parameters =
        c.preset == "earth" ? atmosphere::AtmosphereParameters::earth() : atmosphere::AtmosphereParameters::mars();
    c.model = a.one_of("model", atmosphere::production_quality_names(), c.model);
    atmosphere::AtmosphereParameters& p = c.parameters;
    // The ground is the body's surface; the shell keeps the preset's thickness unless overridden.
    const double thickness = a.number_in("top_altitude_m", 1000.0, 1.0e6, p.top_radius - p.bottom_radius);
    p.name = body.name;
    p.bottom_radius = body.radius_m;
    p.top_radius = body.radius_m + thickness;
    p.rayleigh_scale_height = a.number_in("rayleigh_scale_height_m", 10.0, 1.0e5, p.rayleigh_scale_height);
    p.mie_extinction_at_550nm = a.number_in("mie_extinction_at_550nm", 0.0, 1.0e-2, p.mie_extinction_at_550nm);
    p.mie_scale_height = a.number_in("mie_scale_height_m", 10.0, 1.0e5, p.mie_scale_height);
    p.mie_g = a.number_in("mie_g", -0.99, 0.99, p.mie_g);
    if (a.has("mie_single_scattering_albedo"))
        p.mie_single_scattering_albedo =
            atmosphere::SpectralCurve::constant(a.number_in("mie_single_scattering_albedo", 0.0, 1.0));
    p.ozone_column_dobson = a.number_in("ozone_column_dobson", 0.0, 2000.0, p.ozone_column_dobson);
    if (a.has("ground_albedo"))
        p.ground_albedo = atmosphere::SpectralCurve::constant(a.number_in("ground_albedo", 0.0, 1.0));
    if (p.mie_scale_height >= thickness || p.rayleigh_scale_height >= thickness)
        a.fail("top_altitude_m",
               "the atmosphere (" + std::to_string(thickness) + " m) must be thicker than its scale heights");
    a.reject_unknown_keys();
    return c;
}
}  // namespace

SceneConfig load_scene_config(const std::string& file) {
    SceneConfig s;
    s.file = file;
    const std::string dir = fs::absolute(file).parent_path().string();
    const nlohmann::json doc = JsonReader::parse_file(file);
    JsonReader r(doc, file, "");

    auto bodies = r.array("bodies");
    if (bodies.empty()) r.fail("bodies", "at least one body is required");
    if (bodies.size() > 1000) r.fail("bodies", "at most 1000 bodies");
    std::set<std::string> names;
    for (auto& b : bodies) {
        BodyConfig c;
        c.id = static_cast<uint16_t>(s.bodies.size());
        c.name = b.string("name");
        if (!names.insert(c.name).second) b.fail("name", "body name \"" + c.name + "\" is used twice");
        std::string kind = b.one_of("kind", {"star", "planet", "moon"});
        c.kind = kind == "star" ? BodyKind::Star : kind == "planet" ? BodyKind::Planet : BodyKind::Moon;
        c.ephemeris = b.one_of("ephemeris", {"sun", "earth", "moon", "mercury", "venus", "mars", "jupiter", "saturn",
                                             "uranus", "neptune"});
        c.radius_m = b.number_in("radius_m", 1.0, 1e12);
        std::string tex = b.string("texture", "generated:" + c.name);
        if (tex.rfind("generated:", 0) == 0) {
            c.texture = tex;
        } else {
            c.texture = resolve_path(dir, tex);
            if (!fs::is_regular_file(c.texture))
                b.fail("texture",
                       "image \"" + c.texture +
                           "\" does not exist (install it with scripts/setup.sh, or use \"generated:" + c.name + "\")");
        }
        if (auto t = b.optional_dvec3("tint")) c.tint = glm::vec3(*t);
        c.albedo = b.number_in("albedo", 0.0, 1.0, c.albedo);
        c.limb_darkening_u = b.number_in("limb_darkening_u", 0.0, 1.0, c.limb_darkening_u);
        c.radiance = b.number_in("radiance", 0.0, 1.0e12, c.radiance);
        if (auto u = b.optional_dvec3("umbra_light")) {
            if (glm::any(glm::lessThan(*u, glm::dvec3(0.0))) || glm::any(glm::greaterThan(*u, glm::dvec3(1.0))))
                b.fail("umbra_light", "each component must lie in [0, 1] (light left in the umbra per unit sunlight)");
            c.umbra_light = glm::vec3(*u);
        }
        c.umbra_brightness = b.number_in("umbra_brightness", 0.0, 1.0, c.umbra_brightness);
        c.corona = b.number_in("corona", 0.0, 1.0e6, c.corona);
        if (auto a = b.optional_child("atmosphere")) {
            if (c.kind == BodyKind::Star) a->fail("preset", "a star cannot have an atmosphere");
            c.atmosphere = read_atmosphere(*a, c);
        }
        b.reject_unknown_keys();
        s.bodies.push_back(c);
    }

    auto st = r.child("stars");
    s.stars.catalog = resolve_path(dir, st.string("catalog"));
    if (!fs::is_regular_file(s.stars.catalog)) st.fail("catalog", "file \"" + s.stars.catalog + "\" does not exist");
    s.stars.magnitude_limit = st.number_in("magnitude_limit", -2.0, 12.0, s.stars.magnitude_limit);
    s.stars.psf_sigma_arcmin = st.number_in("psf_sigma_arcmin", 0.01, 600.0, s.stars.psf_sigma_arcmin);
    s.stars.zero_mag_flux = st.number_in("zero_mag_flux", 0.0, 1e6, s.stars.zero_mag_flux);
    st.reject_unknown_keys();
    if (auto sh = r.optional_child("shadows")) s.shadows = read_shadows(*sh, s);
    if (auto g = r.optional_child("glare")) s.glare = read_glare(*g);
    r.reject_unknown_keys();
    return s;
}

}  // namespace cupola
