#include "terrain/terrain_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "overlay/arc_chunks.hpp"

namespace cupola::terrain {

namespace {

constexpr double kHalfPi = 1.5707963267948966192;

// The grid of directions a tile's bound is taken over (5 x 5, corners included), and the largest
// angle between neighbours in it.
constexpr int kBoundGrid = 5;

bool behind_horizon(const TileBound& b, const Relief& relief, const glm::dvec3& camera_m) {
    const double occluder = relief.radius_m() + relief.min_height_m();
    const double d_cam = glm::length(camera_m);
    if (d_cam <= occluder) return false;  // under the lowest relief: nothing is hidden by it
    const double top = relief.radius_m() + relief.max_height_m();
    const double horizon = std::sqrt(d_cam * d_cam - occluder * occluder) + std::sqrt(top * top - occluder * occluder);
    return glm::length(b.centre_m - camera_m) - b.radius_m > horizon;
}

bool outside_every_channel(const TileBound& b, const CutView& view) {
    if (view.channels.empty()) return false;
    const glm::dvec3 to = b.centre_m - view.camera_m;
    const double d = glm::length(to);
    if (d <= b.radius_m) return false;
    const double radius_rad = std::asin(std::min(1.0, b.radius_m / d));
    for (const ChannelCone& c : view.channels)
        if (cone_touches_frustum(c.body_to_channel * (to / d), radius_rad, c.tangents)) return false;
    return true;
}

}  // namespace

uint64_t TerrainCut::hash() const {
    uint64_t h = 1469598103934665603ULL;  // FNV-1a over the tiles' ids
    for (const CutTile& t : tiles) {
        const uint64_t id = t.key.id();
        for (int i = 0; i < 8; ++i) h = (h ^ ((id >> (8 * i)) & 0xff)) * 1099511628211ULL;
    }
    return h;
}

double tile_spacing_m(int level, int segments, double radius_m) {
    return kHalfPi * radius_m / (static_cast<double>(1u << level) * segments);
}

HeightRange tile_height_range(const TileKey& key, const Relief& relief) {
    constexpr int kGrid = 9;
    const double spacing = tile_spacing_m(key.level, kGrid - 1, relief.radius_m());
    HeightRange r{1e300, -1e300};
    int covered = 0;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const glm::dvec3 d = key.direction(i / (kGrid - 1.0), j / (kGrid - 1.0));
            const double h = relief.height_m(d, spacing);
            covered += relief.data_covers(d) ? 1 : 0;
            r.min_m = std::min(r.min_m, h);
            r.max_m = std::max(r.max_m, h);
        }
    // A tile across the data's edge (or a void in it) switches between the data and the whole
    // procedural relief: its surface can take any height of the relief.
    if (relief.has_data() && covered != kGrid * kGrid) return {relief.min_height_m(), relief.max_height_m()};
    const double margin = relief.mesh_error_m(spacing);
    r.min_m = std::max(r.min_m - margin, relief.min_height_m());
    r.max_m = std::min(r.max_m + margin, relief.max_height_m());
    return r;
}

HeightRange TileRangeCache::get(const TileKey& key, const Relief& relief) {
    const auto it = ranges_.find(key.id());
    if (it != ranges_.end()) return it->second;
    if (ranges_.size() >= max_entries_) ranges_.clear();
    return ranges_[key.id()] = tile_height_range(key, relief);
}

TileBound tile_bound(const TileKey& key, const Relief& relief) {
    return tile_bound(key, relief, {relief.min_height_m(), relief.max_height_m()});
}

TileBound tile_bound(const TileKey& key, const Relief& relief, const HeightRange& range) {
    const double lo = relief.radius_m() + range.min_m, hi = relief.radius_m() + range.max_m;
    glm::dvec3 dirs[kBoundGrid * kBoundGrid];
    glm::dvec3 sum(0.0);
    for (int j = 0; j < kBoundGrid; ++j)
        for (int i = 0; i < kBoundGrid; ++i) {
            const glm::dvec3 d = key.direction(i / (kBoundGrid - 1.0), j / (kBoundGrid - 1.0));
            dirs[j * kBoundGrid + i] = d;
            sum += d;
        }
    const glm::dvec3 axis = glm::normalize(sum);
    // The tile's directions all lie within this angle of the axis (plus the largest gap between
    // grid points, which the surface can bulge across).
    double max_angle = 0.0, gap = 0.0;
    for (int k = 0; k < kBoundGrid * kBoundGrid; ++k) {
        max_angle = std::max(max_angle, std::acos(std::clamp(glm::dot(dirs[k], axis), -1.0, 1.0)));
        if (k % kBoundGrid) gap = std::max(gap, std::acos(std::clamp(glm::dot(dirs[k], dirs[k - 1]), -1.0, 1.0)));
        if (k >= kBoundGrid)
            gap = std::max(gap, std::acos(std::clamp(glm::dot(dirs[k], dirs[k - kBoundGrid]), -1.0, 1.0)));
    }
    const double a = std::min(max_angle + gap, kHalfPi);
    // The cap of half-angle a between radii lo and hi: centre on the axis between the cap's rim at
    // lo and its top at hi.
    const double z_lo = lo * std::cos(a), z_hi = hi;
    const double z = 0.5 * (z_lo + z_hi);
    const double rim = hi * std::sin(a);
    TileBound b;
    b.centre_m = axis * z;
    b.radius_m = std::max(
        {std::hypot(rim, hi * std::cos(a) - z), std::hypot(lo * std::sin(a), z_lo - z), z_hi - z, std::abs(z - lo)});
    return b;
}

double screen_error_px(const Relief& relief, int level, const CutView& view, const CutSettings& s, double distance_m) {
    const double h = tile_spacing_m(level, s.segments, relief.radius_m());
    // The chord's sag across a quad's diagonal (sqrt 2 h), where a flat triangle is farthest from
    // the sphere.
    const double error_m = relief.mesh_error_m(h) + h * h / (4.0 * relief.radius_m());
    if (distance_m <= 0.0) return std::numeric_limits<double>::infinity();
    return error_m / (distance_m * view.pixel_rad);
}

double split_distance_m(const Relief& relief, int level, const CutView& view, const CutSettings& s) {
    return screen_error_px(relief, level, view, s, 1.0) / s.budget_px;
}

TerrainCut select_cut(const Relief& relief, const CutView& view, const CutSettings& settings) {
    TileRangeCache ranges;
    return select_cut(relief, view, settings, ranges);
}

TerrainCut select_cut(const Relief& relief, const CutView& view, const CutSettings& settings, TileRangeCache& ranges) {
    if (settings.max_level < 0 || settings.max_level > kMaxTileLevel)
        throw std::invalid_argument("terrain cut: max_level " + std::to_string(settings.max_level) + " is not in 0.." +
                                    std::to_string(kMaxTileLevel));
    TerrainCut cut;
    std::vector<TileKey> stack;
    for (int f = kCubeFaces - 1; f >= 0; --f) stack.push_back({static_cast<CubeFace>(f), 0, 0, 0});
    while (!stack.empty()) {
        const TileKey key = stack.back();
        stack.pop_back();
        const TileBound b = tile_bound(key, relief, ranges.get(key, relief));
        if (behind_horizon(b, relief, view.camera_m)) {
            ++cut.culled_by_horizon;
            continue;
        }
        if (outside_every_channel(b, view)) {
            ++cut.culled_by_frusta;
            continue;
        }
        const double d = std::max(0.0, glm::length(b.centre_m - view.camera_m) - b.radius_m);
        const double e = screen_error_px(relief, key.level, view, settings, d);
        const bool room = cut.tiles.size() + stack.size() + 4 <= settings.max_tiles;
        if (e > settings.budget_px && key.level < settings.max_level && room) {
            const auto kids = key.children();
            for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back(*it);
            continue;
        }
        if (e > settings.budget_px && key.level < settings.max_level) cut.capped = true;
        const double far = key.level == 0 ? std::numeric_limits<double>::infinity()
                                          : split_distance_m(relief, key.level - 1, view, settings);
        cut.tiles.push_back({key, e, d, far});
    }
    std::sort(cut.tiles.begin(), cut.tiles.end(), [](const CutTile& a, const CutTile& b) { return a.key < b.key; });
    return cut;
}

}  // namespace cupola::terrain
