#pragma once
// A tile of the cube-sphere quadtree: face, level and (x, y) of 2^level x 2^level squares on the
// face, x along s and y along t. Level 0 is the whole face.
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>

#include "terrain/cube_sphere.hpp"

namespace cupola::terrain {

constexpr int kMaxTileLevel = 24;  // 2^24 tiles along a face: 0.6 m on the Earth

struct TileKey {
    CubeFace face = CubeFace::PosX;
    int level = 0;
    uint32_t x = 0, y = 0;

    bool operator==(const TileKey& o) const { return face == o.face && level == o.level && x == o.x && y == o.y; }
    bool operator!=(const TileKey& o) const { return !(*this == o); }
    // Face, then level, then y, then x: the order a cut is listed in.
    bool operator<(const TileKey& o) const;

    TileKey parent() const;                   // level 0's parent is itself
    std::array<TileKey, 4> children() const;  // (0,0), (1,0), (0,1), (1,1) in (x, y)
    // (s, t) of the tile's corner at (u, v) in [0, 1]^2 of the tile (0: low s or t).
    glm::dvec2 face_st(double u, double v) const;
    glm::dvec3 direction(double u, double v) const {
        return face_to_direction({face, face_st(u, v).x, face_st(u, v).y});
    }
    // Whether this tile is other or lies inside it.
    bool within(const TileKey& other) const;
    std::string name() const;  // "face/level/x/y"
    uint64_t id() const;       // unique: 3 bits face, 5 bits level, 24 bits each for x and y
};

// The tile of a level that holds a direction.
TileKey tile_at(const glm::dvec3& dir, int level);

}  // namespace cupola::terrain
