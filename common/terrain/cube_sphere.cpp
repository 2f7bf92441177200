#include "terrain/cube_sphere.hpp"

#include <cmath>

namespace cupola::terrain {

namespace {
constexpr double kQuarterPi = 0.78539816339744830962;
}  // namespace

FaceAxes face_axes(CubeFace face) {
    const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    switch (face) {
        case CubeFace::PosX:
            return {x, y, z};
        case CubeFace::NegX:
            return {-x, -y, z};
        case CubeFace::PosY:
            return {y, -x, z};
        case CubeFace::NegY:
            return {-y, x, z};
        case CubeFace::PosZ:
            return {z, x, y};
        case CubeFace::NegZ:
            return {-z, y, x};
    }
    return {x, y, z};
}

glm::dvec3 face_to_direction(const FacePoint& p) {
    const FaceAxes a = face_axes(p.face);
    return glm::normalize(a.n + std::tan(p.s * kQuarterPi) * a.u + std::tan(p.t * kQuarterPi) * a.v);
}

FacePoint direction_to_face(const glm::dvec3& dir) {
    const glm::dvec3 m = glm::abs(dir);
    int axis = 0;
    if (m.y > m[axis]) axis = 1;
    if (m.z > m[axis]) axis = 2;
    FacePoint p;
    p.face = static_cast<CubeFace>(2 * axis + (dir[axis] < 0.0 ? 1 : 0));
    const FaceAxes a = face_axes(p.face);
    const double along_n = glm::dot(dir, a.n);
    p.s = std::atan(glm::dot(dir, a.u) / along_n) / kQuarterPi;
    p.t = std::atan(glm::dot(dir, a.v) / along_n) / kQuarterPi;
    return p;
}

glm::dvec2 direction_to_lat_lon_rad(const glm::dvec3& dir) {
    const glm::dvec3 d = glm::normalize(dir);
    return {std::asin(glm::clamp(d.z, -1.0, 1.0)), std::atan2(d.y, d.x)};
}

glm::dvec3 lat_lon_to_direction(double lat_rad, double lon_rad) {
    const double c = std::cos(lat_rad);
    return {c * std::cos(lon_rad), c * std::sin(lon_rad), std::sin(lat_rad)};
}

}  // namespace cupola::terrain
