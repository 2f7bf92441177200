// Paul Bourke warp meshes (common/calibration/bourke_mesh): an analytic mesh reads back to the
// same map on the fill-layout grid; negative intensity hides nodes; bad files name the line.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "calibration/bourke_mesh.hpp"
#include "calibration/calibration_error.hpp"
#include "calibration/reference_warp.hpp"

using namespace cupola;

namespace {

// Nodes over the whole screen, x in +-aspect, y in +-1; u, v an affine map of x, y (exact under
// piecewise-linear interpolation); intensity falling to the right.
std::string mesh_text(int nx, int ny, double aspect, bool hide_left_column = false) {
    std::ostringstream s;
    s.precision(17);
    s << "2\n" << nx << " " << ny << "\n";
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const double x = aspect * (-1.0 + 2.0 * i / (nx - 1)), y = 1.0 - 2.0 * j / (ny - 1);
            const double u = 0.1 + 0.8 * (x / aspect + 1) / 2, v = 0.2 + 0.6 * (y + 1) / 2;
            const double in = (hide_left_column && i == 0) ? -1.0 : 1.0 - 0.5 * i / (nx - 1);
            s << x << " " << y << " " << u << " " << v << " " << in << "\n";
        }
    return s.str();
}

void expect_error(const std::string& text, const std::string& part) {
    try {
        decode_bourke_mesh(text, "mirror.data", 64, 48);
        ADD_FAILURE() << "no error (" << part << ")";
    } catch (const CalibrationError& e) {
        EXPECT_EQ(e.file(), "mirror.data");
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

}  // namespace

TEST(CalibrationBourke, AffineMeshReadsBackExactly) {
    const ProjectorWarp w = decode_bourke_mesh(mesh_text(9, 7, 64.0 / 48.0), "m.data", 64, 48);
    EXPECT_EQ(w.raster_width, 64);
    EXPECT_EQ(w.raster_height, 48);
    EXPECT_TRUE(w.region_id.empty());
    for (int y = 0; y < 48; y += 5)
        for (int x = 0; x < 64; x += 7) {
            const double px = x + 0.5, py = y + 0.5;
            const glm::dvec2 uv = warp_uv_at(w, px, py);
            // Inside the outer grid point centres the bilinear grid reproduces the affine map.
            const double gx = px * w.grid.columns / 64.0, gy = py * w.grid.rows / 48.0;
            if (gx < 0.5 || gx > w.grid.columns - 0.5 || gy < 0.5 || gy > w.grid.rows - 0.5) continue;
            EXPECT_NEAR(uv.x, 0.1 + 0.8 * px / 64.0, 1e-9);
            EXPECT_NEAR(uv.y, 0.2 + 0.6 * (1.0 - py / 48.0), 1e-9);
        }
    // Intensity is carried per grid point: 1 at the left edge falling to 0.5 at the right.
    EXPECT_GT(w.grid.intensity.front(), w.grid.intensity[w.grid.columns - 1]);
    EXPECT_NEAR(w.grid.intensity.front(), 1.0 - 0.5 * (0.5 / w.grid.columns), 1e-6);
}

TEST(CalibrationBourke, NegativeIntensityHidesNodes) {
    const ProjectorWarp w = decode_bourke_mesh(mesh_text(9, 7, 64.0 / 48.0, true), "m.data", 64, 48);
    EXPECT_TRUE(std::isnan(w.grid.uv[0].x));                      // left edge: not drawn
    EXPECT_TRUE(std::isfinite(w.grid.uv[w.grid.columns - 1].x));  // right edge: drawn
    LinearImage white{4, 4, 1, std::vector<float>(16, 1.0f)};
    const LinearImage out = reference_warp(w, white);
    EXPECT_EQ(out.data[24 * 64 + 0], 0.0f);
    EXPECT_GT(out.data[24 * 64 + 63], 0.4f);
}

TEST(CalibrationBourke, BadFilesNameTheLine) {
    expect_error("", "line 1");
    expect_error("x\n", "mapping type");
    expect_error("2\n3\n", "line 2");
    expect_error("2\n1 5\n", "nx ny");
    const std::string good = mesh_text(3, 3, 64.0 / 48.0);
    expect_error(good.substr(0, good.rfind("\n", good.size() - 2) + 1), "truncated: 8 of 3x3");
    expect_error(good + "0 0 0 0 1\n", "more nodes than");
    expect_error("2\n2 2\n0 0 0 0 1\n0 0 0 0\n0 0 0 0 1\n0 0 0 0 1\n", "line 4");
    expect_error("2\n2 2\n9 9 0 0 1\n9 9 0 0 1\n9 9 0 0 1\n9 9 0 0 1\n", "no drawn triangle");
    EXPECT_THROW(decode_bourke_mesh(good, "m.data", 0, 48), CalibrationError);
}
