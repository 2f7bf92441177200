#include "calibration/bourke_mesh.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "calibration/calibration_error.hpp"
#include "calibration/mesh_resampling.hpp"

namespace cupola {

namespace {

struct BourkeNodes {
    int mapping_type = 0;
    NodeMesh mesh;  // position (x, y) on the screen, value (u, v, intensity)
};

// The next line holding something, with its 1-based number; false at the end.
bool next_line(std::istringstream& in, std::string& line, int& number) {
    while (std::getline(in, line)) {
        ++number;
        if (line.find_first_not_of(" \t\r") != std::string::npos) return true;
    }
    return false;
}

std::string at_line(int n) { return "line " + std::to_string(n); }

BourkeNodes parse_nodes(const std::string& text, const std::string& name) {
    std::istringstream in(text);
    std::string line;
    int n = 0;
    BourkeNodes b;
    if (!next_line(in, line, n)) throw CalibrationError(name, "line 1", "empty file (expected the mapping type)");
    std::istringstream head(line);
    if (!(head >> b.mapping_type)) throw CalibrationError(name, at_line(n), "expected the integer mapping type");
    if (!next_line(in, line, n)) throw CalibrationError(name, at_line(n + 1), "missing 'nx ny'");
    std::istringstream dims(line);
    int nx = 0, ny = 0;
    if (!(dims >> nx >> ny) || nx < 2 || ny < 2 || nx > 4096 || ny > 4096)
        throw CalibrationError(name, at_line(n), "expected 'nx ny', each 2..4096");
    b.mesh = NodeMesh{nx, ny, {}, {}};  // filled as the nodes are read: a short file costs little
    const size_t count = static_cast<size_t>(nx) * ny;
    for (size_t k = 0; k < count; ++k) {
        if (!next_line(in, line, n))
            throw CalibrationError(
                name, at_line(n + 1),
                "truncated: " + std::to_string(k) + " of " + std::to_string(nx) + "x" + std::to_string(ny) + " nodes");
        std::istringstream node(line);
        double x, y, u, v, i;
        if (!(node >> x >> y >> u >> v >> i) || !std::isfinite(x + y + u + v + i))
            throw CalibrationError(name, at_line(n), "expected five numbers 'x y u v i'");
        const double nan = std::numeric_limits<double>::quiet_NaN();
        b.mesh.position.push_back(i < 0.0 ? glm::dvec2(nan) : glm::dvec2(x, y));  // negative i: not drawn
        b.mesh.value.emplace_back(u, v, i);
    }
    if (next_line(in, line, n))
        throw CalibrationError(name, at_line(n), "more nodes than nx*ny = " + std::to_string(nx * ny));
    return b;
}

}  // namespace

ProjectorWarp decode_bourke_mesh(const std::string& text, const std::string& name, int raster_width,
                                 int raster_height) {
    if (raster_width < 1 || raster_height < 1)
        throw CalibrationError(name, "raster size", "the projector raster size must be given (positive)");
    const BourkeNodes b = parse_nodes(text, name);
    const double aspect = static_cast<double>(raster_width) / raster_height;
    // The fill-layout grid: twice the node density (at most one point per pixel).
    const int columns = std::min(raster_width, 2 * b.mesh.columns), rows = std::min(raster_height, 2 * b.mesh.rows);
    const auto values =
        resample_mesh(b.mesh, columns, rows, glm::dvec2((1.0 / columns - 1.0) * aspect, 1.0 - 1.0 / rows),
                      glm::dvec2(2.0 * aspect / columns, -2.0 / rows));
    ProjectorWarp w;
    w.source = name;
    w.raster_width = raster_width;
    w.raster_height = raster_height;
    w.grid = WarpGrid{columns, rows, std::vector<glm::dvec2>(values.size()), std::vector<float>(values.size())};
    size_t drawn = 0;
    for (size_t k = 0; k < values.size(); ++k) {
        w.grid.uv[k] = glm::dvec2(values[k]);
        w.grid.intensity[k] = std::isfinite(values[k].z) ? static_cast<float>(values[k].z) : 0.0f;
        if (std::isfinite(values[k].x)) ++drawn;
    }
    if (drawn == 0)
        throw CalibrationError(name, "nodes", "no drawn triangle covers the raster (x within +-aspect, y within +-1?)");
    return w;
}

ProjectorWarp read_bourke_mesh(const std::string& path, int raster_width, int raster_height) {
    std::ifstream in(path);
    if (!in) throw CalibrationError(path, "", "cannot open the Bourke mesh file");
    std::ostringstream s;
    s << in.rdbuf();
    return decode_bourke_mesh(s.str(), path, raster_width, raster_height);
}

}  // namespace cupola
