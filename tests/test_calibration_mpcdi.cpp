// MPCDI packages (common/calibration/mpcdi_package, mpcdi_writer): one calibration written under
// every reading switch reads back, with the matching switches, to the same ProjectorWarp and the
// same projector image; a mismatched switch gives the predicted different result; the 3d
// profile's frustum becomes the expected ChannelFrustum; bad packages name the file and field.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <zip.h>

#include <cmath>
#include <limits>

#include "calibration/calibration_error.hpp"
#include "calibration/mpcdi_package.hpp"
#include "calibration/mpcdi_writer.hpp"
#include "calibration/reference_warp.hpp"
#include "support/test_support.hpp"

using namespace cupola;

namespace {

const double nan_value = std::numeric_limits<double>::quiet_NaN();

// A smooth, non-affine warp of one region in content (buffer) coordinates, a NaN corner, and
// blend maps whose values survive 8- and 16-bit storage exactly: alpha = (k/255)^gamma.
ProjectorWarp sample_warp(double x0, double x_size, double gamma, bool profile_3d) {
    ProjectorWarp w;
    w.raster_width = 48;
    w.raster_height = 32;
    w.grid = WarpGrid{9, 7, {}, {}};
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 9; ++i) {
            const double s = (i + 0.5) / 9, t = 1.0 - (j + 0.5) / 7;  // t up
            const double lu = 0.05 + 0.9 * s + 0.02 * std::sin(3 * t), lv = 0.1 + 0.8 * t + 0.03 * s * s;
            w.grid.uv.push_back(profile_3d ? glm::dvec2(lu, lv) : glm::dvec2(x0 + x_size * lu, 0.1 + 0.8 * lv));
        }
    w.grid.uv[0] = glm::dvec2(nan_value);
    w.alpha = BlendMap{12, 8, {}};
    w.beta = BlendMap{6, 4, {}};
    for (int k = 0; k < 96; ++k) w.alpha.value.push_back(static_cast<float>(std::pow((k * 2 + 60) / 255.0, gamma)));
    for (int k = 0; k < 24; ++k) w.beta.value.push_back(static_cast<float>(k / 255.0));
    w.projector_gamma = gamma;
    return w;
}

MpcdiPackageOut sample_package(bool profile_3d = false, double gamma = 2.2) {
    MpcdiPackageOut p;
    p.profile = profile_3d ? "3d" : "2d";
    p.geometry_level = 2;
    p.color_level = 2;
    p.buffer_width = 80;
    p.buffer_height = 40;
    for (int r = 0; r < 2; ++r) {
        MpcdiRegionOut out;
        out.id = "proj" + std::to_string(r);
        out.x = 0.4 * r;
        out.y = 0.1;
        out.x_size = 0.6;
        out.y_size = 0.8;
        out.warp = sample_warp(out.x, out.x_size, gamma, profile_3d);
        if (profile_3d) out.warp.frustum = CalibratedFrustum{EulerDeg{-20.0 + 40 * r, 15, 2}, FovDeg{40, 35, 30, 25}};
        p.regions.push_back(out);
    }
    return p;
}

bool both_nan(const glm::dvec2& a, const glm::dvec2& b) { return std::isnan(a.x) && std::isnan(b.x); }

void expect_same_warp(const ProjectorWarp& a, const ProjectorWarp& b, double tol = 1e-6) {
    ASSERT_EQ(a.raster_width, b.raster_width);
    ASSERT_EQ(a.raster_height, b.raster_height);
    ASSERT_EQ(a.grid.columns, b.grid.columns);
    ASSERT_EQ(a.grid.rows, b.grid.rows);
    for (size_t k = 0; k < a.grid.uv.size(); ++k) {
        if (both_nan(a.grid.uv[k], b.grid.uv[k])) continue;
        EXPECT_NEAR(a.grid.uv[k].x, b.grid.uv[k].x, tol) << "point " << k;
        EXPECT_NEAR(a.grid.uv[k].y, b.grid.uv[k].y, tol) << "point " << k;
    }
    for (const auto& [ma, mb] : {std::pair{&a.alpha, &b.alpha}, std::pair{&a.beta, &b.beta}}) {
        ASSERT_EQ(ma->width, mb->width);
        ASSERT_EQ(ma->height, mb->height);
        for (size_t k = 0; k < ma->value.size(); ++k) EXPECT_NEAR(ma->value[k], mb->value[k], tol);
    }
    EXPECT_NEAR(a.projector_gamma, b.projector_gamma, 1e-12);
    ASSERT_EQ(a.frustum.has_value(), b.frustum.has_value());
    if (a.frustum) {
        EXPECT_NEAR(a.frustum->orientation.yaw_deg, b.frustum->orientation.yaw_deg, 1e-12);
        EXPECT_NEAR(a.frustum->orientation.pitch_deg, b.frustum->orientation.pitch_deg, 1e-12);
        EXPECT_NEAR(a.frustum->fov.left_deg, b.frustum->fov.left_deg, 1e-12);
        EXPECT_NEAR(a.frustum->fov.down_deg, b.frustum->fov.down_deg, 1e-12);
    }
}

LinearImage test_content() {
    LinearImage c{40, 20, 3, {}};
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 40; ++x)
            for (int ch = 0; ch < 3; ++ch)
                c.data.push_back(static_cast<float>(0.5 + 0.5 * std::sin(0.3 * x + 0.7 * y + ch)));
    return c;
}

double max_difference(const LinearImage& a, const LinearImage& b) {
    double m = 0.0;
    for (size_t k = 0; k < a.data.size(); ++k) m = std::max(m, static_cast<double>(std::abs(a.data[k] - b.data[k])));
    return m;
}

void replace_entry(const std::string& file, const std::string& entry, const std::string& bytes) {
    int err = 0;
    zip_t* za = zip_open(file.c_str(), 0, &err);
    ASSERT_NE(za, nullptr);
    if (bytes.empty()) {
        zip_delete(za, zip_name_locate(za, entry.c_str(), 0));
    } else {
        zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
        zip_file_add(za, entry.c_str(), src, ZIP_FL_OVERWRITE);
    }
    ASSERT_EQ(zip_close(za), 0);
}

std::string read_entry(const std::string& file, const std::string& entry) {
    int err = 0;
    zip_t* za = zip_open(file.c_str(), ZIP_RDONLY, &err);
    zip_stat_t st;
    zip_stat(za, entry.c_str(), 0, &st);
    std::string s(st.size, '\0');
    zip_file_t* f = zip_fopen(za, entry.c_str(), 0);
    zip_fread(f, s.data(), s.size());
    zip_fclose(f);
    zip_discard(za);
    return s;
}

// The error a package raises, when opened and its region proj0 read.
std::string error_of(const std::string& file, const MpcdiReading& reading = {}) {
    try {
        MpcdiPackage::open(file).read_region("proj0", reading);
    } catch (const CalibrationError& e) {
        EXPECT_EQ(e.file(), file);
        return e.what();
    }
    return "no error";
}

#define EXPECT_CONTAINS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

}  // namespace

TEST(CalibrationMpcdi, EveryReadingOfTheStandardReadsBackTheSameWarp) {
    const std::string dir = test::scratch_dir("calibration_mpcdi_switches");
    for (bool profile_3d : {false, true}) {
        const MpcdiPackageOut p = sample_package(profile_3d);
        const LinearImage content = test_content();
        const LinearImage expected = reference_warp(p.regions[1].warp, content);
        int n = 0;
        for (PfmRows rows : {PfmRows::bottom_first, PfmRows::top_first})
            for (VOrigin v : {VOrigin::bottom, VOrigin::top})
                for (WarpCoordinates c : {WarpCoordinates::region, WarpCoordinates::buffer})
                    for (PfmByteOrder order : {PfmByteOrder::little_endian, PfmByteOrder::big_endian})
                        for (int bits : {8, 16}) {
                            MpcdiWriting w;
                            w.layout = MpcdiReading{rows, v, c, WarpDirection::forward};
                            w.pfm_byte_order = order;
                            w.map_bit_depth = bits;
                            w.map_components = n % 3 == 0 ? 3 : 1;
                            w.gamma_embedded = 2.2;
                            w.v1_level_attribute = n % 2 == 1;
                            w.v1_attribute_case = n % 4 >= 2;
                            const std::string file = dir + "/p" + std::to_string(n++) + ".mpcdi";
                            write_mpcdi(file, p, w);
                            const MpcdiPackage pkg = MpcdiPackage::open(file);
                            ASSERT_EQ(pkg.regions().size(), 2u);
                            EXPECT_EQ(pkg.profile(), p.profile);
                            EXPECT_EQ(pkg.regions()[1].buffer_width, 80);
                            for (int r = 0; r < 2; ++r)
                                expect_same_warp(pkg.read_region(p.regions[r].id, w.layout), p.regions[r].warp);
                            const LinearImage got = reference_warp(pkg.read_region("proj1", w.layout), content);
                            EXPECT_LT(max_difference(got, expected), 1e-5) << file;
                        }
    }
}

TEST(CalibrationMpcdi, MismatchedSwitchesGiveThePredictedWarp) {
    const std::string file = test::scratch_dir("calibration_mpcdi_mismatch") + "/p.mpcdi";
    const MpcdiPackageOut p = sample_package();
    write_mpcdi(file, p, MpcdiWriting{});
    const MpcdiPackage pkg = MpcdiPackage::open(file);
    const WarpGrid& g = p.regions[1].warp.grid;
    const double x = 0.4, xs = 0.6, y = 0.1, ys = 0.8;
    MpcdiReading rows;
    rows.pfm_rows = PfmRows::top_first;
    MpcdiReading vtop;
    vtop.v_origin = VOrigin::top;
    MpcdiReading buffer;
    buffer.coordinates = WarpCoordinates::buffer;
    const WarpGrid a = pkg.read_region("proj1", rows).grid, b = pkg.read_region("proj1", vtop).grid,
                   c = pkg.read_region("proj1", buffer).grid;
    for (int j = 0; j < g.rows; ++j)
        for (int i = 0; i < g.columns; ++i) {
            const glm::dvec2 o = g.uv[j * g.columns + i];
            if (std::isnan(o.x)) continue;
            const glm::dvec2 flipped = a.uv[(g.rows - 1 - j) * g.columns + i];  // rows upside down
            EXPECT_NEAR(flipped.x, o.x, 1e-6);
            EXPECT_NEAR(flipped.y, o.y, 1e-6);
            const glm::dvec2 mirrored = b.uv[j * g.columns + i];  // v measured down in the region
            EXPECT_NEAR(mirrored.y, 2 * y + ys - o.y, 1e-6);
            const glm::dvec2 local = c.uv[j * g.columns + i];  // region-local numbers taken as global
            EXPECT_NEAR(local.x, (o.x - x) / xs, 1e-6);
            EXPECT_NEAR(local.y, (o.y - y) / ys, 1e-6);
        }
}

TEST(CalibrationMpcdi, FrustumBecomesTheExpectedChannelFrustum) {
    const std::string file = test::scratch_dir("calibration_mpcdi_frustum") + "/f.mpcdi";
    MpcdiPackageOut p = sample_package(true);
    write_mpcdi(file, p, MpcdiWriting{});
    // The file holds MPCDI's signed angles: leftAngle and downAngle negative.
    const std::string xml = read_entry(file, "mpcdi.xml");
    EXPECT_CONTAINS(xml, "<leftAngle>-40</leftAngle>");
    EXPECT_CONTAINS(xml, "<downAngle>-25</downAngle>");
    const ProjectorWarp w = MpcdiPackage::open(file).read_region("proj1");
    ASSERT_TRUE(w.frustum);
    const ChannelFrustum f(w.frustum->orientation, w.frustum->fov, 400, 300);
    // The view axis: yaw 20 to the right, pitch 15 up (roll 2 turns about it).
    const double yaw = glm::radians(20.0), pitch = glm::radians(15.0);
    const glm::dvec3 axis(std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw));
    const auto px = f.dome_direction_to_pixel(axis);
    ASSERT_TRUE(px);
    const double tl = std::tan(glm::radians(40.0)), tr = std::tan(glm::radians(35.0)),
                 tu = std::tan(glm::radians(30.0)), td = std::tan(glm::radians(25.0));
    EXPECT_NEAR(px->x, 400 * tl / (tl + tr), 1e-6);
    EXPECT_NEAR(px->y, 300 * tu / (tu + td), 1e-6);
    // The left edge's middle lies 40 degrees from the axis, the top edge's 30.
    const glm::dvec3 left = f.pixel_to_dome_direction({0.0, px->y}), top = f.pixel_to_dome_direction({px->x, 0.0});
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(left, axis))), 40.0, 1e-6);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(top, axis))), 30.0, 1e-6);
    // Yaw is to the right: the left edge is nearer straight ahead (-Z) than the axis.
    EXPECT_GT(-left.z, -axis.z);
    EXPECT_GT(top.y, axis.y);  // the top edge is higher
}

TEST(CalibrationMpcdi, InverseMapsAreInvertedOntoTheProjectorGrid) {
    const std::string file = test::scratch_dir("calibration_mpcdi_inverse") + "/inv.mpcdi";
    // Forward: projector (x, y up) -> content (0.1 + 0.8 x, 0.15 + 0.7 y). Its inverse, sampled
    // over the content grid, is written as the warp's numbers.
    MpcdiPackageOut p;
    MpcdiRegionOut r;
    r.id = "proj0";
    r.warp.raster_width = 40;
    r.warp.raster_height = 30;
    r.warp.grid = WarpGrid{10, 8, {}, {}};
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 10; ++i) {
            const double u = (i + 0.5) / 10, v = 1.0 - (j + 0.5) / 8;
            r.warp.grid.uv.emplace_back((u - 0.1) / 0.8, (v - 0.15) / 0.7);
        }
    p.regions.push_back(r);
    write_mpcdi(file, p, MpcdiWriting{});
    MpcdiReading inverse;
    inverse.warp_direction = WarpDirection::inverse;
    const ProjectorWarp w = MpcdiPackage::open(file).read_region("proj0", inverse);
    ASSERT_EQ(w.grid.columns, 10);
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 10; ++i) {
            const double x = (i + 0.5) / 10, y = 1.0 - (j + 0.5) / 8;
            const glm::dvec2 uv = w.grid.uv[j * 10 + i];
            EXPECT_NEAR(uv.x, 0.1 + 0.8 * x, 1e-6);
            EXPECT_NEAR(uv.y, 0.15 + 0.7 * y, 1e-6);
        }
}

TEST(CalibrationMpcdi, BadPackagesNameFileAndField) {
    const std::string dir = test::scratch_dir("calibration_mpcdi_bad");
    const MpcdiPackageOut good = sample_package();
    auto fresh = [&](const std::string& name, MpcdiPackageOut p) {
        const std::string f = dir + "/" + name + ".mpcdi";
        write_mpcdi(f, p, MpcdiWriting{});
        return f;
    };
    test::write_text(dir + "/notzip.mpcdi", "this is not a zip file");
    EXPECT_CONTAINS(error_of(dir + "/notzip.mpcdi"), "not a readable zip");

    std::string f = fresh("missing", good);
    replace_entry(f, "proj0_alpha.png", "");
    EXPECT_CONTAINS(error_of(f), "region proj0 alphaMap path: 'proj0_alpha.png' is missing");
    f = fresh("noxml", good);
    replace_entry(f, "mpcdi.xml", "");
    EXPECT_CONTAINS(error_of(f), "mpcdi.xml: missing from the package");

    f = fresh("channels", good);
    replace_entry(f, "proj0.pfm", "Pf\n9 7\n-1.0\n" + std::string(9 * 7 * 4, '\0'));
    EXPECT_CONTAINS(error_of(f), "region proj0 geometryWarpFile proj0.pfm PFM channels");
    MpcdiPackageOut p = good;
    p.regions[0].warp.raster_width = 8;  // fewer pixels than grid points
    EXPECT_CONTAINS(error_of(fresh("size", p)), "PFM size: 9x7 points, more than the region's");
    f = fresh("short", good);
    replace_entry(f, "proj0.pfm", "PF\n9 7\n-1.0\n" + std::string(100, '\0'));
    EXPECT_CONTAINS(error_of(f), "PFM data");

    p = good;
    for (auto& uv : p.regions[0].warp.grid.uv) uv = glm::dvec2(nan_value);
    EXPECT_CONTAINS(error_of(fresh("allnan", p)), "every point is NaN");
    p = good;
    for (auto& uv : p.regions[0].warp.grid.uv) uv *= 40.0;  // pixel units
    EXPECT_CONTAINS(error_of(fresh("range", p)), "outside [0,1]");
    p = good;
    for (int k = 0; k + 1 < 63; k += 2) std::swap(p.regions[0].warp.grid.uv[k], p.regions[0].warp.grid.uv[k + 1]);
    EXPECT_CONTAINS(error_of(fresh("folded", p)), "folds over itself");

    const std::string xml = read_entry(fresh("xml", good), "mpcdi.xml");
    auto with_xml = [&](const std::string& name, std::string text, const std::string& from, const std::string& to) {
        const std::string file = fresh(name, good);
        const size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at == std::string::npos) return file;
        replace_entry(file, "mpcdi.xml", text.replace(at, from.size(), to));
        return file;
    };
    EXPECT_CONTAINS(error_of(with_xml("nores", xml, "xResolution=\"48\"", "")),
                    "region proj0 xResolution: missing attribute");
    EXPECT_CONTAINS(error_of(with_xml("noprofile", xml, "profile=\"2d\"", "")), "MPCDI profile: missing attribute");
    EXPECT_CONTAINS(error_of(with_xml("nolevel", xml, "geometry=\"2\"", "")), "MPCDI geometry: missing attribute");
    EXPECT_CONTAINS(error_of(with_xml("badnum", xml, "xSize=\"0.6", "xSize=\"wide")), "xSize: 'wide");
    EXPECT_CONTAINS(error_of(with_xml("nopath", xml, "<path>proj0.pfm</path>", "")), "geometryWarpFile path");
    EXPECT_CONTAINS(error_of(with_xml("broken", xml, "</display>", "")), "not well-formed XML");
    EXPECT_CONTAINS(error_of(with_xml("sl", xml, "profile=\"2d\"", "profile=\"sl\"")), "not supported");
    EXPECT_CONTAINS(error_of(with_xml("bits", xml, "<bitDepth>8</bitDepth>", "<bitDepth>16</bitDepth>")),
                    "bitDepth: mpcdi.xml says 16 bits");

    const std::string fx = read_entry(fresh("fx", sample_package(true)), "mpcdi.xml");
    f = dir + "/magnitudes.mpcdi";
    write_mpcdi(f, sample_package(true), MpcdiWriting{});
    std::string t = fx;
    t.replace(t.find("<leftAngle>-40"), 14, "<leftAngle>40");
    replace_entry(f, "mpcdi.xml", t);
    EXPECT_CONTAINS(error_of(f), "frustum leftAngle: rightAngle must exceed leftAngle");

    try {
        MpcdiPackage::open(fresh("unknown", good)).read_region("nope");
        ADD_FAILURE();
    } catch (const CalibrationError& e) {
        EXPECT_CONTAINS(std::string(e.what()), "region nope: no such region (the package has proj0, proj1)");
    }
    EXPECT_THROW(MpcdiReading{}.set("pfm_rows", "sideways"), std::invalid_argument);
}

TEST(CalibrationMpcdi, SwitchesAreSetFromStrings) {
    MpcdiReading r;
    EXPECT_EQ(r.pfm_rows, PfmRows::bottom_first);
    EXPECT_EQ(r.v_origin, VOrigin::bottom);
    EXPECT_EQ(r.coordinates, WarpCoordinates::region);
    EXPECT_EQ(r.warp_direction, WarpDirection::forward);
    r.set("pfm_rows", "top-first");
    r.set("v_origin", "top");
    r.set("coordinates", "buffer");
    r.set("warp_direction", "inverse");
    EXPECT_EQ(to_string(r.pfm_rows), "top-first");
    EXPECT_EQ(to_string(r.v_origin), "top");
    EXPECT_EQ(to_string(r.coordinates), "buffer");
    EXPECT_EQ(to_string(r.warp_direction), "inverse");
    EXPECT_THROW(r.set("rows", "top-first"), std::invalid_argument);
}

namespace {

void write_exr(const std::string& path, const LinearImage& img) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, img.data.data()));
    out->close();
}

LinearImage read_exr(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const OIIO::ImageSpec& s = in->spec();
    LinearImage img{s.width, s.height, s.nchannels, std::vector<float>(size_t(s.width) * s.height * s.nchannels)};
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, img.data.data());
    return img;
}

}  // namespace

// tools/mpcdi_reference.py reads a package the way PyMPCDI does (first PFM row the top, region-local
// coordinates, alpha = stored^gammaEmbedded); with pfm_rows top-first Cupola's reader and reference
// warp must give the same projector image.
TEST(CalibrationMpcdi, AgreesWithThePyMpcdiReading) {
    const std::string dir = test::scratch_dir("calibration_mpcdi_pympcdi");
    const MpcdiPackageOut p = sample_package();
    MpcdiWriting w;
    w.layout.pfm_rows = PfmRows::top_first;
    w.gamma_embedded = 2.2;
    w.map_bit_depth = 16;
    write_mpcdi(dir + "/p.mpcdi", p, w);
    const LinearImage content = test_content();
    write_exr(dir + "/content.exr", content);
    const std::string python = CUPOLA_SYSTEM_PYTHON3;
    if (test::run_shell(python + " -c 'import numpy, OpenImageIO' 2>&1").first != 0)
        GTEST_SKIP() << python << " lacks numpy or OpenImageIO (scripts/setup.sh installs python3-numpy, "
                     << "python3-openimageio)";
    for (const std::string region : {"proj0", "proj1"}) {
        const auto [rc, output] = test::run_shell(python + " " + test::source_path("tools/mpcdi_reference.py") +
                                                  " --mpcdi " + dir + "/p.mpcdi --region " + region + " --in " + dir +
                                                  "/content.exr --out " + dir + "/" + region + ".exr 2>&1");
        ASSERT_EQ(rc, 0) << output;
        const LinearImage from_python = read_exr(dir + "/" + region + ".exr");
        MpcdiReading r;
        r.pfm_rows = PfmRows::top_first;
        const LinearImage cpp = reference_warp(MpcdiPackage::open(dir + "/p.mpcdi").read_region(region, r), content);
        ASSERT_EQ(from_python.width, cpp.width);
        ASSERT_EQ(from_python.height, cpp.height);
        ASSERT_EQ(from_python.channels, cpp.channels);
        EXPECT_LT(max_difference(from_python, cpp), 1e-5) << region;
        // The default reading (bottom-first) of the same file is upside down: a different image.
        EXPECT_GT(max_difference(reference_warp(MpcdiPackage::open(dir + "/p.mpcdi").read_region(region), content),
                                 from_python),
                  0.05);
    }
}
