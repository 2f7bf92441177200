// The terrain's tile store (common/terrain/tile_store): tiles are built on worker threads, the
// render loop's request never waits for one, a missing tile is drawn as its nearest built
// ancestor (counted), the draw list always covers the cut exactly once, and a tile whose build
// fails is named and left to its ancestor.
#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <stdexcept>

#include "terrain/terrain_cut.hpp"
#include "terrain/tile_store.hpp"

using namespace cupola::terrain;

namespace {
constexpr double kEarth_m = 6371e3;

// A gate the workers wait at until the test opens it: a tile source that is arbitrarily slow.
class Gate {
public:
    void pass() {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [this] { return open_ || budget_ > 0; });
        if (!open_) --budget_;
    }
    void let_through(int n) {
        {
            std::lock_guard<std::mutex> lock(m_);
            budget_ += n;
        }
        cv_.notify_all();
    }
    void open() {
        {
            std::lock_guard<std::mutex> lock(m_);
            open_ = true;
        }
        cv_.notify_all();
    }

private:
    std::mutex m_;
    std::condition_variable cv_;
    bool open_ = false;
    int budget_ = 0;
};

TerrainCut a_cut(const Relief& relief) {
    CutView view;
    view.camera_m = glm::normalize(glm::dvec3(0.6, 0.3, 0.74)) * (kEarth_m + 20e3);
    view.pixel_rad = 2e-3;
    CutSettings s;
    s.segments = 8;
    return select_cut(relief, view, s);
}

// Every cut tile lies in exactly one mesh of the list, and no mesh of the list in another.
void expect_exact_cover(const TerrainCut& cut, const TileDrawList& list) {
    for (const CutTile& t : cut.tiles) {
        int holders = 0;
        for (const auto& m : list.meshes) holders += t.key.within(m->key) ? 1 : 0;
        ASSERT_EQ(holders, 1) << t.key.name();
    }
    for (const auto& a : list.meshes)
        for (const auto& b : list.meshes) {
            if (a != b) {
                ASSERT_FALSE(a->key.within(b->key)) << a->key.name() << " in " << b->key.name();
            }
        }
}
}  // namespace

TEST(TileStore, TheRequestNeverWaitsForABuildAndAncestorsStandInUntilTheTilesArrive) {
    auto relief = std::make_shared<const Relief>(kEarth_m, nullptr, ProceduralRelief{});
    const TerrainCut cut = a_cut(*relief);
    ASSERT_GT(cut.tiles.size(), 20u);
    ASSERT_GT(cut.tiles.front().key.level, 1);
    Gate gate;
    TileStore::Options o;
    o.segments = 8;
    TileStore store(relief, o);
    store.set_build_hook([&](const TileKey&) { gate.pass(); });
    // Every build is held at the gate: the request returns anyway (were it to wait, this test
    // would hang until ctest's timeout), drawing level-0 tiles for the whole cut.
    const TileDrawList first = store.request(cut);
    EXPECT_EQ(first.stand_ins, static_cast<int>(cut.tiles.size()));
    for (const auto& m : first.meshes) EXPECT_EQ(m->key.level, 0);
    expect_exact_cover(cut, first);
    // Some builds through: a mix of the tiles themselves and stand-ins, still an exact cover.
    gate.let_through(static_cast<int>(cut.tiles.size() / 2));
    while (store.stats().built < cut.tiles.size() / 2) std::this_thread::yield();
    const TileDrawList middle = store.request(cut);
    EXPECT_GT(middle.stand_ins, 0);
    EXPECT_LT(middle.stand_ins, static_cast<int>(cut.tiles.size()));
    expect_exact_cover(cut, middle);
    // The ancestors were built first (coarsest first): the stand-ins have sharpened past level 0.
    int above_zero = 0;
    for (const auto& m : middle.meshes) above_zero += m->key.level > 0 ? 1 : 0;
    EXPECT_GT(above_zero, static_cast<int>(middle.meshes.size()) / 2);
    // All through: the cut itself, no stand-in.
    gate.open();
    store.wait_idle();
    const TileDrawList last = store.request(cut);
    EXPECT_EQ(last.stand_ins, 0);
    ASSERT_EQ(last.meshes.size(), cut.tiles.size());
    for (size_t i = 0; i < cut.tiles.size(); ++i) EXPECT_EQ(last.meshes[i]->key, cut.tiles[i].key);
    const TileStoreStats s = store.stats();
    std::printf("tile store: %zu cached (%zu bytes), %llu built, %llu of %llu frames with stand-ins\n", s.cached,
                s.cached_bytes, static_cast<unsigned long long>(s.built),
                static_cast<unsigned long long>(s.fallback_frames), static_cast<unsigned long long>(s.frames));
    EXPECT_EQ(s.frames, 3u);
    EXPECT_EQ(s.fallback_frames, 2u);
    EXPECT_GE(s.built, cut.tiles.size());  // and the ancestors that stood in on the way
    EXPECT_EQ(s.failed, 0u);
}

TEST(TileStore, TheCacheIsBoundedAndAFailedBuildIsNamedAndLeftToItsAncestor) {
    auto relief = std::make_shared<const Relief>(kEarth_m, nullptr, ProceduralRelief{});
    const TerrainCut cut = a_cut(*relief);
    TileStore::Options o;
    o.segments = 8;
    o.capacity = 16;
    TileStore store(relief, o);
    const TileKey bad = cut.tiles[cut.tiles.size() / 2].key;
    store.set_build_hook([&](const TileKey& k) {
        if (k == bad) throw std::runtime_error("elevation block unreadable");
    });
    store.request(cut);
    store.wait_idle();
    const TileStoreStats s = store.stats();
    EXPECT_LE(s.cached, 16u);
    EXPECT_GT(s.evicted, 0u);
    EXPECT_EQ(s.failed, 1u);
    EXPECT_NE(s.first_failure.find("tile " + bad.name() + ": elevation block unreadable"), std::string::npos)
        << s.first_failure;
    // The failed tile is drawn as an ancestor, and not queued again.
    const TileDrawList list = store.request(cut);
    expect_exact_cover(cut, list);
    EXPECT_GT(list.stand_ins, 0);
    store.wait_idle();
    EXPECT_EQ(store.stats().failed, 1u);
}
