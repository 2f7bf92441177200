#pragma once
// Tile meshes built on worker threads and kept in a bounded cache; the render loop asks for a
// cut's tiles and never waits for a build or a file read. A tile not built yet is drawn as its
// nearest built ancestor (the six level-0 tiles are built before the store is returned, so there
// always is one), which then stands in for every tile of the cut under it; the frames in which
// that happened are counted. A missing tile's unbuilt ancestors are queued with it and builds run
// coarsest first, so a stand-in sharpens level by level. A tile whose build fails is not asked
// for again: its nearest built ancestor stays in.
//
// While tiles load, two nodes can draw different stand-ins for a few frames (each still covers
// the cut exactly once); once every node has built the cut, all draw the same tiles.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "terrain/terrain_cut.hpp"
#include "terrain/tile_mesh.hpp"

namespace cupola::terrain {

struct TileStoreStats {
    size_t cached = 0, queued = 0, capacity = 0;
    size_t cached_bytes = 0;  // the meshes' CPU memory
    uint64_t built = 0, evicted = 0;
    uint64_t frames = 0, fallback_frames = 0;  // requests, and those that drew an ancestor
    uint64_t failed = 0;                       // builds that threw (a block read failed)
    std::string first_failure;                 // the first one's message, naming the tile
};

struct TileDrawList {
    std::vector<std::shared_ptr<const TileMesh>> meshes;  // disjoint; together they cover the cut
    int stand_ins = 0;                                    // cut tiles drawn as an ancestor this frame
};

class TileStore {
public:
    struct Options {
        int workers = 2;
        size_t capacity = 3000;  // meshes kept (above a cut's tiles; 87 kB each at 32 segments with the horizon), least
                                 // recently drawn out first
        int segments = 32;
        bool horizon = false;  // each mesh with its horizon map, for the relief's shadows (tile_horizon.hpp)
    };
    TileStore(std::shared_ptr<const Relief> relief, const Options& options);
    ~TileStore();
    TileStore(const TileStore&) = delete;
    TileStore& operator=(const TileStore&) = delete;

    // What to draw for a cut now; queues the tiles that are missing. Never waits on a build.
    TileDrawList request(const TerrainCut& cut);
    // Blocks until nothing is queued or being built (tests and offline rendering).
    void wait_idle();
    TileStoreStats stats() const;
    // A test hook: called by a worker before it builds each tile (a slow disk: block or sleep here).
    void set_build_hook(std::function<void(const TileKey&)> hook);

private:
    std::shared_ptr<const TileMesh> nearest_built(const TileKey& key);
    void queue_missing(const std::vector<TileKey>& keys);
    void want(const TileKey& key, int stand_in_level, std::vector<TileKey>& missing) const;
    void work();
    void finish(const TileKey& key, const std::shared_ptr<const TileMesh>& mesh, const std::string& failure);
    void keep(const std::shared_ptr<const TileMesh>& mesh);
    void touch(uint64_t id);

    std::shared_ptr<const Relief> relief_;
    Options options_;
    mutable std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::deque<TileKey> queue_;
    std::unordered_set<uint64_t> pending_;  // queued or being built
    std::unordered_set<uint64_t> failed_;
    int building_ = 0;
    bool stopping_ = false;
    std::list<uint64_t> recent_;  // most recently drawn first
    struct Entry {
        std::shared_ptr<const TileMesh> mesh;
        std::list<uint64_t>::iterator at;
    };
    std::unordered_map<uint64_t, Entry> cache_;
    std::function<void(const TileKey&)> hook_;
    TileStoreStats stats_;
    std::vector<std::thread> workers_;
};

}  // namespace cupola::terrain
