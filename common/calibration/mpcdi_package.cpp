#include "calibration/mpcdi_package.hpp"

#include <strings.h>

#include <cmath>
#include <fstream>
#include <pugixml.hpp>
#include <spdlog/spdlog.h>
#include <sstream>

#include "calibration/blend_map_file.hpp"
#include "calibration/calibration_error.hpp"
#include "calibration/mpcdi_frustum.hpp"
#include "calibration/warp_grid_reading.hpp"
#include "calibration/zip_archive.hpp"

namespace cupola {

// Reads mpcdi.xml into the package's fields. Attribute and element names are compared ignoring
// case (VESA MPCDI v2.0 (2015) §3.5.2: 2.0 writes xResolution, 1.0 files Xresolution).
struct MpcdiPackageParser {
    const std::string& name;

    static pugi::xml_attribute attr(pugi::xml_node n, const char* key) {
        for (pugi::xml_attribute a : n.attributes())
            if (strcasecmp(a.name(), key) == 0) return a;
        return {};
    }
    static pugi::xml_node child(pugi::xml_node n, const char* key) {
        for (pugi::xml_node c : n.children())
            if (c.type() == pugi::node_element && strcasecmp(c.name(), key) == 0) return c;
        return {};
    }

    std::string text_attr(pugi::xml_node n, const char* key, const std::string& where) const {
        pugi::xml_attribute a = attr(n, key);
        if (!a) throw CalibrationError(name, where + " " + key, "missing attribute");
        return a.value();
    }
    double number(const std::string& text, const std::string& field) const {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v))
            throw CalibrationError(name, field, "'" + text + "' is not a number");
        return v;
    }
    double number_attr(pugi::xml_node n, const char* key, const std::string& where) const {
        return number(text_attr(n, key, where), where + " " + key);
    }
    int int_attr(pugi::xml_node n, const char* key, const std::string& where, int lo, int hi) const {
        const double v = number_attr(n, key, where);
        if (v != std::floor(v) || v < lo || v > hi)
            throw CalibrationError(name, where + " " + key,
                                   "must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
        return static_cast<int>(v);
    }
    double number_child(pugi::xml_node n, const char* key, const std::string& where) const {
        pugi::xml_node c = child(n, key);
        if (!c) throw CalibrationError(name, where + " " + key, "missing element");
        return number(c.text().get(), where + " " + key);
    }

    int int_child(pugi::xml_node n, const char* key, const std::string& where,
                  std::initializer_list<int> allowed) const {
        const double v = number_child(n, key, where);
        for (int a : allowed)
            if (v == a) return a;
        std::string list;
        for (int a : allowed) list += (list.empty() ? "" : " or ") + std::to_string(a);
        throw CalibrationError(name, where + " " + key, "must be " + list);
    }

    void parse_root(pugi::xml_node root, MpcdiPackage& p) const;
    CalibratedFrustum parse_frustum(pugi::xml_node f, const std::string& where) const;
    MpcdiRegionInfo parse_region(pugi::xml_node r, const MpcdiRegionInfo& buffer, bool profile_3d) const;
    void parse_display(pugi::xml_node root, MpcdiPackage& p) const;
    MpcdiFileRef parse_file_ref(pugi::xml_node f, const std::string& where, bool with_gamma) const;
    void parse_files(pugi::xml_node root, MpcdiPackage& p) const;
};

void MpcdiPackageParser::parse_root(pugi::xml_node root, MpcdiPackage& p) const {
    p.profile_ = text_attr(root, "profile", "MPCDI");
    if (p.profile_ == "a3" || p.profile_ == "sl")
        throw CalibrationError(name, "MPCDI profile", "'" + p.profile_ + "' is not supported (2d, 3d)");
    if (p.profile_ != "2d" && p.profile_ != "3d")
        throw CalibrationError(name, "MPCDI profile", "'" + p.profile_ + "' is not a profile (2d, 3d)");
    if (attr(root, "geometry") || !attr(root, "level")) {
        p.geometry_level_ = int_attr(root, "geometry", "MPCDI", 1, 4);
        p.color_level_ = attr(root, "color") ? int_attr(root, "color", "MPCDI", 1, 5) : 1;
    } else {  // MPCDI v1 (and Scalable's library): one level for both
        p.geometry_level_ = p.color_level_ = int_attr(root, "level", "MPCDI", 1, 4);
    }
}

CalibratedFrustum MpcdiPackageParser::parse_frustum(pugi::xml_node f, const std::string& where) const {
    const std::string w = where + " frustum";
    MpcdiFrustumAngles a;
    a.yaw = number_child(f, "yaw", w);
    a.pitch = number_child(f, "pitch", w);
    a.roll = number_child(f, "roll", w);
    a.right_angle = number_child(f, "rightAngle", w);
    a.left_angle = number_child(f, "leftAngle", w);
    a.up_angle = number_child(f, "upAngle", w);
    a.down_angle = number_child(f, "downAngle", w);
    try {
        return frustum_from_mpcdi(a, name);
    } catch (const CalibrationError& e) {
        throw CalibrationError(name, where + " " + e.field(), e.message());
    }
}

MpcdiRegionInfo MpcdiPackageParser::parse_region(pugi::xml_node r, const MpcdiRegionInfo& buffer,
                                                 bool profile_3d) const {
    MpcdiRegionInfo info = buffer;
    info.id = text_attr(r, "id", "buffer " + buffer.buffer_id + " region");
    const std::string where = "region " + info.id;
    info.x = number_attr(r, "x", where);
    info.y = number_attr(r, "y", where);
    info.x_size = number_attr(r, "xSize", where);
    info.y_size = number_attr(r, "ySize", where);
    if (!(info.x_size > 0.0) || !(info.y_size > 0.0))
        throw CalibrationError(name, where + " xSize/ySize", "must be positive");
    info.x_resolution = int_attr(r, "xResolution", where, 1, 65536);
    info.y_resolution = int_attr(r, "yResolution", where, 1, 65536);
    pugi::xml_node f = child(r, "frustum");
    if (f) info.frustum = parse_frustum(f, where);
    if (profile_3d && !f) throw CalibrationError(name, where + " frustum", "missing (the 3d profile needs one)");
    return info;
}

void MpcdiPackageParser::parse_display(pugi::xml_node root, MpcdiPackage& p) const {
    pugi::xml_node display = child(root, "display");
    if (!display) throw CalibrationError(name, "MPCDI display", "missing element");
    for (pugi::xml_node b : display.children()) {
        if (b.type() != pugi::node_element || strcasecmp(b.name(), "buffer") != 0) continue;
        MpcdiRegionInfo buffer;
        buffer.buffer_id = text_attr(b, "id", "buffer");
        buffer.buffer_width = int_attr(b, "xResolution", "buffer " + buffer.buffer_id, 1, 65536);
        buffer.buffer_height = int_attr(b, "yResolution", "buffer " + buffer.buffer_id, 1, 65536);
        for (pugi::xml_node r : b.children())
            if (r.type() == pugi::node_element && strcasecmp(r.name(), "region") == 0)
                p.regions_.push_back(parse_region(r, buffer, p.profile_ == "3d"));
    }
    if (p.regions_.empty()) throw CalibrationError(name, "MPCDI display", "no buffer with a region");
}

MpcdiFileRef MpcdiPackageParser::parse_file_ref(pugi::xml_node f, const std::string& where, bool with_gamma) const {
    MpcdiFileRef ref;
    ref.given = true;
    pugi::xml_node path = child(f, "path");
    if (!path || std::string(path.text().get()).empty())
        throw CalibrationError(name, where + " path", "missing element");
    ref.path = path.text().get();
    if (child(f, "componentDepth")) ref.component_depth = int_child(f, "componentDepth", where, {1, 3});
    if (child(f, "bitDepth")) ref.bit_depth = int_child(f, "bitDepth", where, {8, 16});
    if (with_gamma && child(f, "gammaEmbedded")) {
        ref.gamma_embedded = number_child(f, "gammaEmbedded", where);
        ref.gamma_embedded_given = true;
    }
    return ref;
}

void MpcdiPackageParser::parse_files(pugi::xml_node root, MpcdiPackage& p) const {
    pugi::xml_node files = child(root, "files");
    if (!files) throw CalibrationError(name, "MPCDI files", "missing element");
    for (pugi::xml_node fs : files.children()) {
        if (fs.type() != pugi::node_element || strcasecmp(fs.name(), "fileset") != 0) continue;
        const std::string region = text_attr(fs, "region", "fileset");
        MpcdiRegionInfo* info = nullptr;
        for (MpcdiRegionInfo& r : p.regions_)
            if (r.id == region) info = &r;
        if (!info) throw CalibrationError(name, "fileset " + region, "names no region of the display");
        const std::string where = "fileset " + region;
        pugi::xml_node warp = child(fs, "geometryWarpFile");
        if (!warp) throw CalibrationError(name, where + " geometryWarpFile", "missing element");
        info->warp_file = parse_file_ref(warp, where + " geometryWarpFile", false);
        if (pugi::xml_node a = child(fs, "alphaMap")) info->alpha_map = parse_file_ref(a, where + " alphaMap", true);
        if (pugi::xml_node b = child(fs, "betaMap")) info->beta_map = parse_file_ref(b, where + " betaMap", false);
    }
}

MpcdiPackage MpcdiPackage::from_bytes(const std::string& bytes, const std::string& name) {
    MpcdiPackage p;
    p.name_ = name;
    p.zip_bytes_ = bytes;
    const std::string xml = ZipArchive(p.zip_bytes_, name).read("mpcdi.xml");
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed = doc.load_buffer(xml.data(), xml.size());
    if (!parsed)
        throw CalibrationError(
            name, "mpcdi.xml",
            std::string("not well-formed XML at byte ") + std::to_string(parsed.offset) + ": " + parsed.description());
    pugi::xml_node root = MpcdiPackageParser::child(doc, "MPCDI");
    if (!root) throw CalibrationError(name, "mpcdi.xml", "no <MPCDI> root element");
    const MpcdiPackageParser parser{name};
    parser.parse_root(root, p);
    parser.parse_display(root, p);
    parser.parse_files(root, p);
    return p;
}

MpcdiPackage MpcdiPackage::open(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw CalibrationError(file, "", "cannot open the MPCDI package");
    std::ostringstream s;
    s << in.rdbuf();
    return from_bytes(s.str(), file);
}

std::string MpcdiPackage::entry(const std::string& path, const std::string& field) const {
    const ZipArchive zip(zip_bytes_, name_);
    if (!zip.contains(path))
        throw CalibrationError(name_, field + " path", "'" + path + "' is missing from the package");
    return zip.read(path);
}

namespace {

// Runs a step that reads one file of the package; its errors name the package and, as the field,
// `part` (which file of which region) followed by the field within that file.
template <class Step>
auto within(const std::string& package, const std::string& part, Step&& step) {
    try {
        return step();
    } catch (const CalibrationError& e) {
        throw CalibrationError(package, part + (e.field().empty() ? "" : " " + e.field()), e.message());
    }
}

BlendMapEncoding encoding(const MpcdiFileRef& ref) {
    return BlendMapEncoding{ref.bit_depth, ref.component_depth, ref.gamma_embedded};
}

}  // namespace

ProjectorWarp MpcdiPackage::read_region(const std::string& region_id, const MpcdiReading& reading) const {
    const MpcdiRegionInfo* info = nullptr;
    std::string known;
    for (const MpcdiRegionInfo& r : regions_) {
        if (r.id == region_id) info = &r;
        known += (known.empty() ? "" : ", ") + r.id;
    }
    if (!info) throw CalibrationError(name_, "region " + region_id, "no such region (the package has " + known + ")");
    const std::string where = "region " + region_id;
    if (!info->warp_file.given) throw CalibrationError(name_, where + " fileset", "no geometryWarpFile for it");
    ProjectorWarp w;
    w.source = name_ + " region " + region_id;
    w.region_id = region_id;
    w.raster_width = info->x_resolution;
    w.raster_height = info->y_resolution;
    w.frustum = info->frustum;
    const MpcdiFileRef& wf = info->warp_file;
    const std::string pfm_part = where + " geometryWarpFile " + wf.path;
    const std::string pfm_bytes = entry(wf.path, where + " geometryWarpFile");
    const PfmImage pfm = within(name_, pfm_part, [&] { return decode_pfm(pfm_bytes, wf.path, reading.pfm_rows); });
    if (geometry_level_ == 1 && (pfm.width > 32 || pfm.height > 32))
        spdlog::warn("{}: {}: {}x{} points, more than geometry level 1's 32x32", name_, pfm_part, pfm.width,
                     pfm.height);
    const WarpGridReading grid_reading{WarpFileFrame{profile_ == "3d", info->x, info->y, info->x_size, info->y_size,
                                                     reading.v_origin, reading.coordinates},
                                       reading.warp_direction, w.raster_width, w.raster_height};
    w.grid = within(name_, pfm_part, [&] { return warp_grid_from_pfm(pfm, grid_reading, wf.path); });
    if (info->alpha_map.given) {
        const MpcdiFileRef& a = info->alpha_map;
        const std::string bytes = entry(a.path, where + " alphaMap");
        w.alpha =
            within(name_, where + " alphaMap " + a.path, [&] { return decode_blend_map(bytes, a.path, encoding(a)); });
        if (a.gamma_embedded_given) w.projector_gamma = a.gamma_embedded;
    }
    if (info->beta_map.given) {
        const MpcdiFileRef& b = info->beta_map;
        const std::string bytes = entry(b.path, where + " betaMap");
        w.beta =
            within(name_, where + " betaMap " + b.path, [&] { return decode_blend_map(bytes, b.path, encoding(b)); });
    }
    return w;
}

}  // namespace cupola
