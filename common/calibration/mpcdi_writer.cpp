#include "calibration/mpcdi_writer.hpp"

#include <zip.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <pugixml.hpp>
#include <sstream>

#include "calibration/blend_map_file.hpp"
#include "calibration/calibration_error.hpp"
#include "calibration/mpcdi_coordinates.hpp"
#include "calibration/mpcdi_frustum.hpp"

namespace cupola {

namespace {

using Entries = std::vector<std::pair<std::string, std::string>>;  // zip entry name -> bytes

WarpFileFrame file_frame(const MpcdiPackageOut& p, const MpcdiRegionOut& r, const MpcdiReading& layout) {
    return WarpFileFrame{p.profile == "3d", r.x, r.y, r.x_size, r.y_size, layout.v_origin, layout.coordinates};
}

void check_region(const std::string& file, const MpcdiRegionOut& r) {
    const WarpGrid& g = r.warp.grid;
    const std::string where = "region " + r.id;
    if (r.id.empty()) throw CalibrationError(file, "region id", "empty");
    if (g.columns < 2 || g.rows < 2 || g.uv.size() != static_cast<size_t>(g.columns) * g.rows)
        throw CalibrationError(file, where + " grid", "needs at least 2x2 points, columns*rows of them");
    if (!g.intensity.empty())
        throw CalibrationError(file, where + " intensity", "MPCDI has no per-point intensity: fold it into alpha");
    if (r.warp.raster_width < 1 || r.warp.raster_height < 1)
        throw CalibrationError(file, where + " xResolution", "the raster size must be positive");
    if (!(r.x_size > 0.0) || !(r.y_size > 0.0))
        throw CalibrationError(file, where + " xSize", "the region's size must be positive");
}

// The warp grid as the file stores it: (u, v, error), NaN points (NaN, NaN, 1) as VESA MPCDI v2.0 (2015) says.
PfmImage warp_pfm(const MpcdiRegionOut& r, const WarpFileFrame& frame) {
    const WarpGrid& g = r.warp.grid;
    PfmImage img{g.columns, g.rows, 3, std::vector<float>(g.uv.size() * 3)};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t k = 0; k < g.uv.size(); ++k) {
        const glm::dvec2 c = g.uv[k];
        const bool shown = std::isfinite(c.x) && std::isfinite(c.y);
        const glm::dvec2 f = shown ? content_to_file(frame, c) : glm::dvec2(0.0);
        img.data[3 * k] = shown ? static_cast<float>(f.x) : nan;
        img.data[3 * k + 1] = shown ? static_cast<float>(f.y) : nan;
        img.data[3 * k + 2] = shown ? 0.0f : 1.0f;
    }
    return img;
}

// The shortest text that reads back to exactly v.
std::string number(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

void add_text(pugi::xml_node parent, const char* name, const std::string& text) {
    parent.append_child(name).text().set(text.c_str());
}

void add_frustum(pugi::xml_node region, const CalibratedFrustum& f) {
    const MpcdiFrustumAngles a = frustum_to_mpcdi(f);
    pugi::xml_node x = region.append_child("frustum");
    add_text(x, "yaw", number(a.yaw));
    add_text(x, "pitch", number(a.pitch));
    add_text(x, "roll", number(a.roll));
    add_text(x, "rightAngle", number(a.right_angle));
    add_text(x, "leftAngle", number(a.left_angle));
    add_text(x, "upAngle", number(a.up_angle));
    add_text(x, "downAngle", number(a.down_angle));
}

void add_root(pugi::xml_document& doc, const MpcdiPackageOut& p, const MpcdiWriting& w) {
    pugi::xml_node root = doc.append_child("MPCDI");
    root.append_attribute("profile") = p.profile.c_str();
    if (w.v1_level_attribute) {
        root.append_attribute("level") = std::max(p.geometry_level, p.color_level);
        root.append_attribute("version") = "1.0";
    } else {
        root.append_attribute("geometry") = p.geometry_level;
        root.append_attribute("color") = p.color_level;
        root.append_attribute("version") = "2.0";
    }
    root.append_child("display");
    root.append_child("files");
}

pugi::xml_node buffer_node(pugi::xml_node display, const MpcdiPackageOut& p, const std::string& id,
                           const MpcdiWriting& w) {
    for (pugi::xml_node b : display.children("buffer"))
        if (id == b.attribute("id").value()) return b;
    int width = p.buffer_width, height = p.buffer_height;
    for (const MpcdiRegionOut& r : p.regions) {
        if (p.buffer_width == 0) width = std::max(width, r.warp.raster_width);
        if (p.buffer_height == 0) height = std::max(height, r.warp.raster_height);
    }
    pugi::xml_node b = display.append_child("buffer");
    b.append_attribute("id") = id.c_str();
    b.append_attribute(w.v1_attribute_case ? "Xresolution" : "xResolution") = width;
    b.append_attribute(w.v1_attribute_case ? "Yresolution" : "yResolution") = height;
    return b;
}

void add_region(pugi::xml_node buffer, const MpcdiPackageOut& p, const MpcdiRegionOut& r, const MpcdiWriting& w) {
    pugi::xml_node x = buffer.append_child("region");
    x.append_attribute("id") = r.id.c_str();
    x.append_attribute("x") = number(r.x).c_str();
    x.append_attribute("y") = number(r.y).c_str();
    x.append_attribute(w.v1_attribute_case ? "xsize" : "xSize") = number(r.x_size).c_str();
    x.append_attribute(w.v1_attribute_case ? "ysize" : "ySize") = number(r.y_size).c_str();
    x.append_attribute(w.v1_attribute_case ? "Xresolution" : "xResolution") = r.warp.raster_width;
    x.append_attribute(w.v1_attribute_case ? "Yresolution" : "yResolution") = r.warp.raster_height;
    if (p.profile == "3d" && r.warp.frustum) add_frustum(x, *r.warp.frustum);
}

void add_map(pugi::xml_node fileset, const char* element, const std::string& path, const BlendMapEncoding& e,
             bool with_gamma) {
    pugi::xml_node m = fileset.append_child(element);
    add_text(m, "path", path);
    add_text(m, "componentDepth", std::to_string(e.components));
    add_text(m, "bitDepth", std::to_string(e.bit_depth));
    if (with_gamma) add_text(m, "gammaEmbedded", number(e.gamma_embedded));
}

void add_files(pugi::xml_node files, const MpcdiPackageOut& p, const MpcdiRegionOut& r, const MpcdiWriting& w,
               Entries& entries) {
    pugi::xml_node fs = files.append_child("fileset");
    fs.append_attribute("region") = r.id.c_str();
    pugi::xml_node g = fs.append_child("geometryWarpFile");
    add_text(g, "path", r.id + ".pfm");
    add_text(g, "interpolation", "linear");
    entries.emplace_back(r.id + ".pfm",
                         encode_pfm(warp_pfm(r, file_frame(p, r, w.layout)), w.layout.pfm_rows, w.pfm_byte_order));
    const BlendMapEncoding alpha{w.map_bit_depth, w.map_components, w.gamma_embedded};
    const BlendMapEncoding beta{w.map_bit_depth, w.map_components, 1.0};
    if (!r.warp.alpha.empty()) {
        add_map(fs, "alphaMap", r.id + "_alpha.png", alpha, true);
        entries.emplace_back(r.id + "_alpha.png", encode_blend_map(r.warp.alpha, r.id + " alphaMap", alpha));
    }
    if (!r.warp.beta.empty()) {
        add_map(fs, "betaMap", r.id + "_beta.png", beta, false);
        entries.emplace_back(r.id + "_beta.png", encode_blend_map(r.warp.beta, r.id + " betaMap", beta));
    }
}

void write_zip(const std::string& file, const Entries& entries) {
    int err = 0;
    zip_t* za = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    if (!za) throw CalibrationError(file, "", "cannot create the zip (libzip error " + std::to_string(err) + ")");
    for (const auto& [name, bytes] : entries) {
        zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
        if (!src || zip_file_add(za, name.c_str(), src, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8) < 0) {
            const std::string why = zip_strerror(za);
            if (src) zip_source_free(src);
            zip_discard(za);
            throw CalibrationError(file, name, "cannot add to the zip: " + why);
        }
    }
    if (zip_close(za) < 0) {
        const std::string why = zip_strerror(za);
        zip_discard(za);
        throw CalibrationError(file, "", "cannot write the zip: " + why);
    }
}

}  // namespace

void write_mpcdi(const std::string& file, const MpcdiPackageOut& package, const MpcdiWriting& writing) {
    if (package.profile != "2d" && package.profile != "3d")
        throw CalibrationError(file, "profile", "'" + package.profile + "': the writer writes 2d or 3d");
    pugi::xml_document doc;
    add_root(doc, package, writing);
    pugi::xml_node root = doc.child("MPCDI");
    Entries entries;
    for (const MpcdiRegionOut& r : package.regions) {
        check_region(file, r);
        add_region(buffer_node(root.child("display"), package, r.buffer_id, writing), package, r, writing);
        add_files(root.child("files"), package, r, writing, entries);
    }
    std::ostringstream xml;
    doc.save(xml, "  ", pugi::format_default, pugi::encoding_utf8);
    entries.insert(entries.begin(), {"mpcdi.xml", xml.str()});
    write_zip(file, entries);
}

}  // namespace cupola
