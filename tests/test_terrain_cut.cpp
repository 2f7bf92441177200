// The terrain cut chosen once for the whole dome (common/terrain/terrain_cut, cluster_cut_view,
// tile_mesh): every node computes the same tiles, they cover every pixel of every channel that
// sees the ground, exactly once, and the mesh they draw is within the error budget of the finest
// mesh of the same relief, at every morph between a tile and its parent.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <random>

#include "config/cluster_config.hpp"
#include "support/test_support.hpp"
#include "terrain/cluster_cut_view.hpp"
#include "terrain/terrain_cut.hpp"
#include "terrain/tile_mesh.hpp"

using namespace cupola;
using namespace cupola::terrain;

namespace {
constexpr double kDeg = 0.017453292519943295769;
constexpr double kEarth_m = 6371e3;

// An observer height_m above the reference sphere at (lat, lon), looking toward azimuth az_deg
// (from north, east positive) and pitched up by pitch_deg: the camera orientation and position.
struct Observer {
    glm::dvec3 position_m;
    glm::dquat orientation;
};
Observer observer(double lat_deg, double lon_deg, double height_m, double az_deg, double pitch_deg) {
    const glm::dvec3 up = lat_lon_to_direction(lat_deg * kDeg, lon_deg * kDeg);
    const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), up));
    const glm::dvec3 north = glm::cross(up, east);
    const double a = az_deg * kDeg, p = pitch_deg * kDeg;
    const glm::dvec3 horizontal = std::cos(a) * north + std::sin(a) * east;
    const glm::dvec3 forward = std::cos(p) * horizontal + std::sin(p) * up;
    const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
    const glm::dvec3 cam_up = glm::cross(right, forward);
    return {up * (kEarth_m + height_m), glm::quat_cast(glm::dmat3(right, cam_up, -forward))};
}

// The distance along a ray to a sphere about the origin, or -1.
double ray_sphere(const glm::dvec3& o, const glm::dvec3& d, double r) {
    const double b = glm::dot(o, d), c = glm::dot(o, o) - r * r, disc = b * b - c;
    if (disc < 0.0) return -1.0;
    const double t = -b - std::sqrt(disc);
    return t > 0.0 ? t : -1.0;
}

ProceduralRelief alpine() {
    ProceduralRelief p;
    p.base_wavelength_m = 100e3;
    p.base_amplitude_m = 1200.0;
    p.gain = 0.55;
    return p;
}
}  // namespace

TEST(TerrainCut, EveryNodeChoosesTheSameCutAndItCoversEveryChannelOnce) {
    const std::string config = test::source_path("configs/dome-4ch.json");
    const Relief relief(kEarth_m, nullptr, alpine());
    // A dome tilted so the low ground fills its front, 2 km up over the Alps, looking south.
    const Observer o = observer(46.5, 10.0, 2000.0, 180.0, -20.0);
    CutSettings s;
    s.budget_px = 1.0;
    // Each channel's node loads the cluster itself and computes the cut from the snapshot.
    const ClusterConfig cluster = load_cluster_config(config);
    std::vector<uint64_t> hashes;
    TerrainCut cut;
    std::vector<uint64_t> own_channel_hashes;
    for (size_t c = 0; c < cluster.channels.size(); ++c) {
        ClusterConfig own = load_cluster_config(config);
        // The order the channels are listed in is no input to the cut: each node lists its own first.
        std::rotate(own.channels.begin(), own.channels.begin() + static_cast<long>(c), own.channels.end());
        cut = select_cut(relief, cut_view_for_cluster(own, o.position_m, glm::dmat3(1.0), o.orientation), s);
        hashes.push_back(cut.hash());
        // What a per-channel choice would give that node (for contrast).
        own_channel_hashes.push_back(
            select_cut(relief, cut_view_for_channel(own, own.channels[0], o.position_m, glm::dmat3(1.0), o.orientation),
                       s)
                .hash());
    }
    for (uint64_t h : hashes) EXPECT_EQ(h, hashes.front());
    int differ = 0;
    for (uint64_t h : own_channel_hashes) differ += h != hashes.front() ? 1 : 0;
    EXPECT_EQ(differ, static_cast<int>(cluster.channels.size()));  // no channel alone gives the dome's cut
    std::printf("cut: %zu tiles (levels %d..%d), %d behind the horizon, %d outside every channel, capped %d\n",
                cut.tiles.size(), cut.tiles.front().key.level, cut.tiles.back().key.level, cut.culled_by_horizon,
                cut.culled_by_frusta, cut.capped);
    ASSERT_FALSE(cut.capped);
    EXPECT_GT(cut.culled_by_horizon + cut.culled_by_frusta, 0);
    // No tile lies inside another.
    for (size_t i = 0; i < cut.tiles.size(); ++i)
        for (size_t j = 0; j < cut.tiles.size(); ++j) {
            if (i != j) {
                ASSERT_FALSE(cut.tiles[i].key.within(cut.tiles[j].key)) << cut.tiles[i].key.name();
            }
        }
    // Every pixel of every channel whose ray meets the lowest relief lands in a tile of the cut
    // (the culling never drops ground a channel sees), pixels on channel edges included.
    std::map<uint64_t, int> by_id;
    for (const CutTile& t : cut.tiles) by_id[t.key.id()] = t.key.level;
    const glm::dmat3 to_world = glm::mat3_cast(o.orientation) * dome_tilt_rotation(cluster.dome.tilt_deg);
    const double lowest = kEarth_m + relief.min_height_m();
    int ground = 0;
    for (const ChannelConfig& ch : cluster.channels) {
        const ChannelFrustum f = ch.frustum();
        for (int y = 0; y <= f.height(); y += 4)
            for (int x = 0; x <= f.width(); x += 4) {
                const glm::dvec3 d = to_world * f.pixel_to_dome_direction(glm::dvec2(x, y));
                const double t = ray_sphere(o.position_m, d, lowest);
                if (t < 0.0) continue;
                ++ground;
                const glm::dvec3 hit = glm::normalize(o.position_m + t * d);
                bool found = false;
                for (int level = 0; level <= s.max_level && !found; ++level)
                    found = by_id.count(tile_at(hit, level).id()) > 0;
                ASSERT_TRUE(found) << ch.name << " pixel " << x << "," << y;
            }
    }
    EXPECT_GT(ground, 1000);
}

TEST(TerrainCut, TheMeshIsWithinTheBudgetOfTheFinestMeshAtEveryMorph) {
    const Relief relief(kEarth_m, nullptr, alpine());
    const ClusterConfig cluster = load_cluster_config(test::source_path("configs/dome-4ch.json"));
    const Observer o = observer(46.5, 10.0, 1500.0, 90.0, -25.0);
    const CutView view = cut_view_for_cluster(cluster, o.position_m, glm::dmat3(1.0), o.orientation);
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (double budget : {1.0, 4.0}) {
        CutSettings s;
        s.budget_px = budget;
        const TerrainCut cut = select_cut(relief, view, s);
        ASSERT_FALSE(cut.capped);
        double worst = 0.0;
        for (size_t i = 0; i < cut.tiles.size(); i += std::max<size_t>(1, cut.tiles.size() / 40)) {
            const CutTile& t = cut.tiles[i];
            const TileMesh m = build_tile_mesh(t.key, relief, s.segments);
            for (int k = 0; k < 200; ++k) {
                const double a = u(rng), b = u(rng);
                const glm::dvec3 dir = t.key.direction(a, b);
                const double reference = relief.height_m(dir, 0.0);
                const double d = glm::length(dir * (kEarth_m + reference) - o.position_m);
                // The morph the GPU applies at this distance: own shape near, the parent's far.
                const double morph = std::clamp((t.morph_far_m - d) / (0.3 * t.morph_far_m), 0.0, 1.0);
                const double e_px = std::abs(m.height_on_mesh_m(a, b, morph) - reference) / (d * view.pixel_rad);
                worst = std::max(worst, e_px);
            }
        }
        std::printf("budget %.1f px: %zu tiles, largest measured error %.3f px\n", budget, cut.tiles.size(), worst);
        EXPECT_LE(worst, budget);
        EXPECT_GT(worst, 0.02 * budget);  // the model is not wildly pessimistic either
    }
}

TEST(TileMesh, SkirtsHangBelowTheEdgeAndTheParentShapeMatchesTheParentsMesh) {
    const Relief relief(kEarth_m, nullptr, alpine());
    const TileKey key{CubeFace::PosX, 9, 100, 301};
    const TileMesh m = build_tile_mesh(key, relief, 16);
    const TileMesh parent = build_tile_mesh(key.parent(), relief, 16);
    // At morph 0 the child has its parent's shape: compare at points of the child's quarter.
    const glm::dvec2 lo = key.face_st(0, 0), plo = key.parent().face_st(0, 0), phi = key.parent().face_st(1, 1);
    for (double a : {0.0, 0.13, 0.5, 0.77, 1.0})
        for (double b : {0.0, 0.31, 0.5, 0.9, 1.0}) {
            const glm::dvec2 st = lo + glm::dvec2(a, b) * (key.face_st(1, 1) - lo);
            const glm::dvec2 pu = (st - plo) / (phi - plo);
            EXPECT_NEAR(m.height_on_mesh_m(a, b, 0.0), parent.height_on_mesh_m(pu.x, pu.y, 1.0), 1e-6) << a << " " << b;
        }
    // A vertex the parent lacks morphs onto the parent's flat edge (its chord in 3-D), not onto the
    // averaged height along its own direction (h^2 / 2R above the chord: metres at level 9).
    const int cx = static_cast<int>(key.x % 2) * 8, cy = static_cast<int>(key.y % 2) * 8;
    const glm::dvec3 chord_mid = 0.5 * (parent.position_m(cx, cy) + parent.position_m(cx + 1, cy));
    EXPECT_LT(glm::length(m.parent_position_m(1, 0) - chord_mid), 1e-6);
    EXPECT_LT(glm::length(m.position_m(1, 0, 0.0) - chord_mid), 1e-6);
    // The skirt: one vertex below each edge vertex, skirt_depth_m lower, and triangles for it.
    const auto v = m.gpu_vertices();
    ASSERT_EQ(v.size(), 17u * 17u + 4u * 16u);
    EXPECT_GT(m.skirt_depth_m, 0.0);
    const glm::dvec3 top = glm::dvec3(v[0].position) + m.centre_m, low = glm::dvec3(v[17 * 17].position) + m.centre_m;
    EXPECT_NEAR(glm::length(top) - glm::length(low), m.skirt_depth_m, 0.05);
    EXPECT_EQ(m.triangle_indices().size(), 16u * 16u * 6u + 4u * 16u * 6u);
    // Floats relative to the centre: a tile at level 9 is about 20 km across, the positions are
    // within it (not planet-sized numbers that lose their metres in a float).
    for (const auto& g : v) EXPECT_LT(glm::length(g.position), 30e3f);
    // Every vertex, in its own shape and its parent's, the skirt too, lies within the mesh's bound,
    // and the bound is tight (within the skirt's depth and a metre of the farthest vertex).
    double farthest = 0.0;
    for (const auto& g : v)
        for (const glm::vec3 p : {g.position, g.position + g.parent_delta}) {
            EXPECT_LE(glm::length(glm::dvec3(p)), m.bound_radius_m);
            farthest = std::max(farthest, static_cast<double>(glm::length(p)));
        }
    EXPECT_LT(m.bound_radius_m, farthest + m.skirt_depth_m + 1.0);
}

TEST(TileMesh, NormalsFollowTheSlopeAndNeighboursAgreeAlongTheirEdge) {
    // A flat relief: every normal is the vertical.
    ProceduralRelief flat;
    flat.base_amplitude_m = 0.0;
    const Relief level(kEarth_m, nullptr, flat);
    const TileKey key{CubeFace::PosZ, 7, 40, 90};
    const TileMesh m0 = build_tile_mesh(key, level, 8);
    for (size_t k = 0; k < m0.normals.size(); ++k) EXPECT_GT(glm::dot(m0.normals[k], m0.directions[k]), 1.0 - 1e-12);
    // A relief: a normal leans away from the uphill side (toward where the ground falls),
    // and two neighbours of a level give the same normal where they share an edge.
    const Relief relief(kEarth_m, nullptr, alpine());
    const TileMesh a = build_tile_mesh(key, relief, 8), b = build_tile_mesh({key.face, 7, 41, 90}, relief, 8);
    for (int j = 0; j <= 8; ++j) EXPECT_LT(glm::length(a.normals[a.index(8, j)] - b.normals[b.index(0, j)]), 1e-9) << j;
    int leaning = 0;
    for (int j = 1; j < 8; ++j)
        for (int i = 1; i < 8; ++i) {
            const glm::dvec3 rise = a.position_m(i + 1, j) - a.position_m(i - 1, j);
            const glm::dvec3 up = a.directions[a.index(i, j)];
            const double slope = glm::dot(rise, up);  // > 0: uphill toward +i
            if (std::abs(slope) < 1.0) continue;
            ++leaning;
            const glm::dvec3 across = rise - glm::dot(rise, up) * up;  // horizontal, toward +i
            EXPECT_LT(glm::dot(a.normals[a.index(i, j)], across) * slope, 0.0) << i << " " << j;
        }
    EXPECT_GT(leaning, 10);
    // The GPU's vertices carry them, the skirt its edge vertex's.
    const auto v = a.gpu_vertices();
    EXPECT_LT(glm::length(glm::dvec3(v[0].normal) - a.normals[0]), 1e-6);
    EXPECT_LT(glm::length(glm::dvec3(v[81].normal) - a.normals[0]), 1e-6);
}
