#include "terrain/tile_key.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace cupola::terrain {

bool TileKey::operator<(const TileKey& o) const {
    return std::make_tuple(static_cast<int>(face), level, y, x) <
           std::make_tuple(static_cast<int>(o.face), o.level, o.y, o.x);
}

TileKey TileKey::parent() const {
    if (level == 0) return *this;
    return {face, level - 1, x / 2, y / 2};
}

std::array<TileKey, 4> TileKey::children() const {
    const uint32_t cx = 2 * x, cy = 2 * y;
    return {TileKey{face, level + 1, cx, cy}, TileKey{face, level + 1, cx + 1, cy},
            TileKey{face, level + 1, cx, cy + 1}, TileKey{face, level + 1, cx + 1, cy + 1}};
}

glm::dvec2 TileKey::face_st(double u, double v) const {
    const double size = 2.0 / static_cast<double>(1u << level);
    return {-1.0 + (x + u) * size, -1.0 + (y + v) * size};
}

bool TileKey::within(const TileKey& other) const {
    if (face != other.face || level < other.level) return false;
    const int shift = level - other.level;
    return (x >> shift) == other.x && (y >> shift) == other.y;
}

std::string TileKey::name() const {
    return std::to_string(static_cast<int>(face)) + "/" + std::to_string(level) + "/" + std::to_string(x) + "/" +
           std::to_string(y);
}

uint64_t TileKey::id() const {
    return (static_cast<uint64_t>(face) << 61) | (static_cast<uint64_t>(level) << 56) |
           (static_cast<uint64_t>(x) << 24) | static_cast<uint64_t>(y);
}

TileKey tile_at(const glm::dvec3& dir, int level) {
    const FacePoint p = direction_to_face(dir);
    const uint32_t n = 1u << level;
    const auto index = [n](double c) {
        return static_cast<uint32_t>(std::clamp(std::floor((c + 1.0) * 0.5 * n), 0.0, static_cast<double>(n - 1)));
    };
    return {p.face, level, index(p.s), index(p.t)};
}

}  // namespace cupola::terrain
