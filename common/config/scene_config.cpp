#include "config/scene_config.hpp"

#include <filesystem>
#include <set>

#include "config/cluster_config.hpp"
#include "config/json_reader.hpp"

namespace cupola {

namespace fs = std::filesystem;

const BodyConfig* SceneConfig::find(const std::string& name) const {
    for (const auto& b : bodies)
        if (b.name == name) return &b;
    return nullptr;
}

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
        c.ephemeris = b.one_of("ephemeris", {"sun", "earth", "moon"});
        c.radius_m = b.number_in("radius_m", 1.0, 1e12);
        std::string tex = b.string("texture", "generated:" + c.name);
        if (tex.rfind("generated:", 0) == 0) {
            c.texture = tex;
        } else {
            c.texture = resolve_path(dir, tex);
            if (!fs::is_regular_file(c.texture))
                b.fail("texture", "image \"" + c.texture + "\" does not exist (install it with scripts/setup.sh, or use \"generated:" + c.name + "\")");
        }
        if (auto t = b.optional_dvec3("tint")) c.tint = glm::vec3(*t);
        c.albedo = b.number_in("albedo", 0.0, 1.0, c.albedo);
        c.limb_darkening_u = b.number_in("limb_darkening_u", 0.0, 1.0, c.limb_darkening_u);
        c.radiance = b.number_in("radiance", 0.0, 6.0e4, c.radiance);
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
    r.reject_unknown_keys();
    return s;
}

}  // namespace cupola
