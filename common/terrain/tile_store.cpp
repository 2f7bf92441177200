#include "terrain/tile_store.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cupola::terrain {

namespace {
size_t mesh_bytes(const TileMesh& m) {
    return (m.directions.size() + m.normals.size()) * sizeof(glm::dvec3) +
           (m.height_m.size() + m.parent_height_m.size()) * sizeof(double) + m.horizon.size() * sizeof(glm::vec4);
}
}  // namespace

TileStore::TileStore(std::shared_ptr<const Relief> relief, const Options& options)
    : relief_(std::move(relief)), options_(options) {
    if (options.workers < 1 || options.workers > 64)
        throw std::invalid_argument("tile store: " + std::to_string(options.workers) + " workers (1..64)");
    if (options.capacity < 6) throw std::invalid_argument("tile store: a capacity under the six level-0 tiles");
    stats_.capacity = options.capacity;
    for (int f = 0; f < kCubeFaces; ++f) {
        const TileKey root{static_cast<CubeFace>(f), 0, 0, 0};
        keep(std::make_shared<const TileMesh>(build_tile_mesh(root, *relief_, options_.segments, options_.horizon)));
    }
    for (int i = 0; i < options.workers; ++i) workers_.emplace_back([this] { work(); });
}

TileStore::~TileStore() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    idle_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void TileStore::touch(uint64_t id) {
    auto it = cache_.find(id);
    if (it != cache_.end()) recent_.splice(recent_.begin(), recent_, it->second.at);
}

// Under the lock. Level-0 tiles are never evicted (they are every tile's last stand-in).
void TileStore::keep(const std::shared_ptr<const TileMesh>& mesh) {
    recent_.push_front(mesh->key.id());
    cache_[mesh->key.id()] = {mesh, recent_.begin()};
    stats_.cached_bytes += mesh_bytes(*mesh);
    for (auto it = std::prev(recent_.end()); cache_.size() > options_.capacity && it != recent_.begin();) {
        auto victim = it--;
        const auto entry = cache_.find(*victim);
        if (entry->second.mesh->key.level == 0) continue;
        stats_.cached_bytes -= mesh_bytes(*entry->second.mesh);
        cache_.erase(entry);
        recent_.erase(victim);
        ++stats_.evicted;
    }
    stats_.cached = cache_.size();
}

// Under the lock: the tile's mesh or its nearest ancestor's.
std::shared_ptr<const TileMesh> TileStore::nearest_built(const TileKey& key) {
    for (TileKey k = key;; k = k.parent()) {
        const auto it = cache_.find(k.id());
        if (it != cache_.end()) return it->second.mesh;
        if (k.level == 0) return nullptr;
    }
}

// Under the lock.
void TileStore::queue_missing(const std::vector<TileKey>& keys) {
    for (const TileKey& k : keys)
        if (!cache_.count(k.id()) && !failed_.count(k.id()) && pending_.insert(k.id()).second) queue_.push_back(k);
    std::stable_sort(queue_.begin(), queue_.end(),
                     [](const TileKey& a, const TileKey& b) { return a.level < b.level; });
    stats_.queued = queue_.size();
}

// Under the lock: the missing tile and its unbuilt ancestors below the stand-in, so that the
// stand-in sharpens level by level (the queue is coarsest first).
void TileStore::want(const TileKey& key, int stand_in_level, std::vector<TileKey>& missing) const {
    for (TileKey k = key; k.level > stand_in_level; k = k.parent())
        if (!cache_.count(k.id())) missing.push_back(k);
}

TileDrawList TileStore::request(const TerrainCut& cut) {
    TileDrawList out;
    std::vector<TileKey> missing;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        std::unordered_map<uint64_t, std::shared_ptr<const TileMesh>> chosen;
        for (const CutTile& t : cut.tiles) {
            std::shared_ptr<const TileMesh> m = nearest_built(t.key);
            if (!m) continue;
            if (m->key != t.key) want(t.key, m->key.level, missing);
            chosen.emplace(m->key.id(), m);
        }
        // An ancestor stands in for everything under it: drop the chosen tiles inside another.
        for (const auto& [id, m] : chosen) {
            bool inside = false;
            for (TileKey k = m->key; k.level > 0 && !inside;) {
                k = k.parent();
                inside = chosen.count(k.id()) > 0;
            }
            if (!inside) out.meshes.push_back(m);
            touch(id);
        }
        std::sort(out.meshes.begin(), out.meshes.end(), [](const auto& a, const auto& b) { return a->key < b->key; });
        // Every cut tile not drawn as itself: missing, or built but under a stand-in.
        std::unordered_set<uint64_t> drawn;
        for (const auto& m : out.meshes) drawn.insert(m->key.id());
        for (const CutTile& t : cut.tiles) out.stand_ins += drawn.count(t.key.id()) ? 0 : 1;
        queue_missing(missing);
        ++stats_.frames;
        if (out.stand_ins > 0) ++stats_.fallback_frames;
    }
    if (!missing.empty()) wake_.notify_all();
    return out;
}

void TileStore::work() {
    for (;;) {
        TileKey key;
        std::function<void(const TileKey&)> hook;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            key = queue_.front();
            queue_.pop_front();
            stats_.queued = queue_.size();
            ++building_;
            hook = hook_;
        }
        std::shared_ptr<const TileMesh> mesh;
        std::string failure;
        try {
            if (hook) hook(key);
            mesh =
                std::make_shared<const TileMesh>(build_tile_mesh(key, *relief_, options_.segments, options_.horizon));
        } catch (const std::exception& e) {
            failure = e.what();
        } catch (...) {
            failure = "an exception that is not a std::exception";
        }
        finish(key, mesh, failure);
    }
}

// A built tile joins the cache; a failed one is not asked for again (its ancestor stays in).
void TileStore::finish(const TileKey& key, const std::shared_ptr<const TileMesh>& mesh, const std::string& failure) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (mesh) {
            keep(mesh);
            ++stats_.built;
        } else {
            failed_.insert(key.id());
            ++stats_.failed;
            if (stats_.first_failure.empty()) stats_.first_failure = "tile " + key.name() + ": " + failure;
        }
        pending_.erase(key.id());
        --building_;
    }
    idle_.notify_all();
}

void TileStore::wait_idle() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return stopping_ || (queue_.empty() && building_ == 0); });
}

TileStoreStats TileStore::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
}

void TileStore::set_build_hook(std::function<void(const TileKey&)> hook) {
    std::lock_guard<std::mutex> lock(mutex_);
    hook_ = std::move(hook);
}

}  // namespace cupola::terrain
