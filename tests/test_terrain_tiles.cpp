// The terrain's cube-sphere quadtree (common/terrain/cube_sphere, tile_key, terrain_cut's bound):
// faces round-trip, tiles nest and tile the sphere, and a tile's bounding sphere holds it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "terrain/cube_sphere.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_key.hpp"

using namespace cupola::terrain;

namespace {
constexpr double kPi = 3.14159265358979323846;

glm::dvec3 random_direction(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    return glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
}
}  // namespace

TEST(CubeSphere, FacePointsAndDirectionsRoundTrip) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 d = random_direction(rng);
        const FacePoint p = direction_to_face(d);
        ASSERT_LE(std::abs(p.s), 1.0 + 1e-12);
        ASSERT_LE(std::abs(p.t), 1.0 + 1e-12);
        ASSERT_LT(glm::length(face_to_direction(p) - d), 1e-14) << i;
    }
    // Each face's axes are right-handed and its centre is its normal.
    for (int f = 0; f < kCubeFaces; ++f) {
        const FaceAxes a = face_axes(static_cast<CubeFace>(f));
        EXPECT_LT(glm::length(glm::cross(a.u, a.v) - a.n), 1e-15) << f;
        EXPECT_LT(glm::length(face_to_direction({static_cast<CubeFace>(f), 0.0, 0.0}) - a.n), 1e-15) << f;
    }
}

TEST(CubeSphere, NeighbouringFacesMeetAlongTheirEdges) {
    // The edge s = 1 of +X is the edge s = -1 of +Y: the same directions, no gap.
    for (double t = -1.0; t <= 1.0; t += 0.125) {
        const glm::dvec3 a = face_to_direction({CubeFace::PosX, 1.0, t});
        const FacePoint q = direction_to_face(a + glm::dvec3(-1e-9, 1e-9, 0.0));
        EXPECT_EQ(q.face, CubeFace::PosY) << t;
        EXPECT_NEAR(q.s, -1.0, 1e-8) << t;
        EXPECT_NEAR(q.t, t, 1e-8) << t;
    }
}

TEST(CubeSphere, EquiangularCellsAreWithinOnePointThreeOfEachOtherInArea) {
    // The area of a cell of a 64 x 64 face grid, at the centre and in the corner.
    const auto cell_area = [](int i, int j) {
        const double step = 2.0 / 64;
        const FacePoint p{CubeFace::PosZ, -1.0 + i * step, -1.0 + j * step};
        const glm::dvec3 a = face_to_direction(p), b = face_to_direction({p.face, p.s + step, p.t}),
                         c = face_to_direction({p.face, p.s, p.t + step});
        return glm::length(glm::cross(b - a, c - a));
    };
    const double ratio = cell_area(32, 32) / cell_area(0, 0);
    std::printf("equiangular cube: centre cell / corner cell area = %.3f (gnomonic: 5.196)\n", ratio);
    EXPECT_GT(ratio, 1.2);
    EXPECT_LT(ratio, 1.35);
}

TEST(TileKey, ChildrenNestAndTileTheirParentAndLevelsTileTheSphere) {
    const TileKey k{CubeFace::NegY, 5, 17, 9};
    for (const TileKey& c : k.children()) {
        EXPECT_EQ(c.parent(), k);
        EXPECT_TRUE(c.within(k));
        EXPECT_FALSE(k.within(c));
    }
    EXPECT_EQ(k.children()[3].face_st(1.0, 1.0), k.face_st(1.0, 1.0));
    EXPECT_EQ(k.children()[0].face_st(0.0, 0.0), k.face_st(0.0, 0.0));
    // Every direction is in exactly the tile tile_at names, and its corners hold it.
    std::mt19937_64 rng(3);
    std::set<uint64_t> ids;
    for (int i = 0; i < 5000; ++i) {
        const glm::dvec3 d = random_direction(rng);
        const TileKey t = tile_at(d, 6);
        ids.insert(t.id());
        const FacePoint p = direction_to_face(d);
        const glm::dvec2 lo = t.face_st(0, 0), hi = t.face_st(1, 1);
        ASSERT_EQ(p.face, t.face);
        ASSERT_TRUE(p.s >= lo.x && p.s <= hi.x && p.t >= lo.y && p.t <= hi.y) << t.name();
        ASSERT_TRUE(t.within(tile_at(d, 2)));
    }
    EXPECT_GT(ids.size(), 3000u);  // 24576 tiles at level 6: the samples spread over them
    EXPECT_EQ(TileKey({CubeFace::PosZ, 3, 5, 6}).name(), "4/3/5/6");
}

TEST(TileBound, HoldsEveryPointOfTheTileAtEveryHeight) {
    ProceduralRelief p;
    p.base_amplitude_m = 4000.0;
    const Relief relief(6371e3, nullptr, p);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const TileKey& key : {TileKey{CubeFace::PosX, 0, 0, 0}, TileKey{CubeFace::PosZ, 1, 1, 0},
                               TileKey{CubeFace::NegZ, 4, 3, 15}, TileKey{CubeFace::PosY, 12, 4000, 17}}) {
        const TileBound b = tile_bound(key, relief);
        for (int i = 0; i < 4000; ++i) {
            const double r = relief.radius_m() + (u(rng) < 0.5 ? relief.min_height_m() : relief.max_height_m());
            const glm::dvec3 q = key.direction(u(rng), u(rng)) * r;
            ASSERT_LE(glm::length(q - b.centre_m), b.radius_m * (1 + 1e-12)) << key.name();
        }
        // Not wastefully large: within the tile's own extent (its diagonal) plus the relief's range.
        const double extent = glm::length(key.direction(0, 0) - key.direction(1, 1)) * relief.radius_m();
        EXPECT_LT(b.radius_m, extent + relief.max_height_m() - relief.min_height_m()) << key.name();
    }
}
