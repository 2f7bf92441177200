#pragma once
// The cut through the tile quadtree that a frame draws, chosen once for the whole cluster: the
// error of a tile is measured against the dome's finest pixel, from the camera's position, never
// from one channel's projection, and a tile is culled only when no channel of the dome can see it.
// Every node computes it from the snapshot and the cluster's configuration alone, so every
// channel draws the same tiles and the seams between channels cannot crack or pop.
//
// Refinement: a tile is split while its screen-space error, the relief's mesh error at the tile's
// sample spacing over the distance to the tile's bounding sphere in units of the finest pixel,
// exceeds the budget (Roettger et al. 1998, section 3; on a sphere: Schafhitzel et al. 2007,
// section 5; Sperlhofer 2011, section 4.4.2). Culling: beyond the horizon of the sphere the lowest
// relief reaches (farther than the tangent from the camera plus the tangent from the highest
// relief), or outside every channel's frustum.
#include <glm/glm.hpp>

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "terrain/relief.hpp"
#include "terrain/tile_key.hpp"

namespace cupola::terrain {

// One channel of the dome as the body sees it: body frame -> channel frame (+X right, +Y up,
// -Z forward), and its frustum's tangents (left, right, down, up).
struct ChannelCone {
    glm::dmat3 body_to_channel{1.0};
    glm::dvec4 tangents{1.0};
};

struct CutView {
    glm::dvec3 camera_m{0.0};           // body-fixed, from the body's centre
    std::vector<ChannelCone> channels;  // the whole dome; empty: no frustum culling
    double pixel_rad = 1e-3;            // the dome's finest pixel, as an angle
};

struct CutSettings {
    double budget_px = 1.0;  // the largest screen-space error allowed
    int segments = 32;       // quads along a tile's side
    int max_level = 20;
    size_t max_tiles = 4096;  // past this the refinement stops (reported)
};

struct CutTile {
    TileKey key;
    double error_px = 0.0;     // its screen-space error from the camera
    double distance_m = 0.0;   // camera to its bounding sphere (0 inside it)
    double morph_far_m = 0.0;  // a vertex this far or farther takes its parent's shape (geomorphing)
};

struct TerrainCut {
    std::vector<CutTile> tiles;  // in TileKey order
    int culled_by_horizon = 0, culled_by_frusta = 0;
    bool capped = false;    // max_tiles stopped the refinement somewhere
    uint64_t hash() const;  // of the keys, for comparing the cuts of two nodes
};

struct TileBound {
    glm::dvec3 centre_m{0.0};
    double radius_m = 0.0;
};

// The sample spacing (m, the largest along a tile side) of a level's tiles.
double tile_spacing_m(int level, int segments, double radius_m);
// The heights a tile's surface can take: the range of a 9 x 9 grid of its heights widened by the
// relief's mesh error at that grid's spacing (what the surface can do between the samples).
struct HeightRange {
    double min_m = 0.0, max_m = 0.0;
};
HeightRange tile_height_range(const TileKey& key, const Relief& relief);
// A sphere that holds the tile at every height in the range (default: the whole relief's range).
TileBound tile_bound(const TileKey& key, const Relief& relief);
TileBound tile_bound(const TileKey& key, const Relief& relief, const HeightRange& range);

// Tiles' height ranges kept between frames (they depend only on the tile and the relief): the
// cut is the same whatever this holds, it only saves the sampling. Cleared past max_entries.
class TileRangeCache {
public:
    explicit TileRangeCache(size_t max_entries = 200000) : max_entries_(max_entries) {}
    HeightRange get(const TileKey& key, const Relief& relief);
    size_t size() const { return ranges_.size(); }

private:
    size_t max_entries_;
    std::unordered_map<uint64_t, HeightRange> ranges_;
};
// The screen-space error (px) of a level's tiles at a distance, and the distance within which a
// level's tiles are split.
double screen_error_px(const Relief& relief, int level, const CutView& view, const CutSettings& s, double distance_m);
double split_distance_m(const Relief& relief, int level, const CutView& view, const CutSettings& s);

TerrainCut select_cut(const Relief& relief, const CutView& view, const CutSettings& settings, TileRangeCache& ranges);
TerrainCut select_cut(const Relief& relief, const CutView& view, const CutSettings& settings);

}  // namespace cupola::terrain
