#include "passes/body_map.hpp"

#include <fmt/format.h>

#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

namespace cupola {

namespace {

std::string map_key(const std::string& texture, const glm::dvec3& tint) {
    return fmt::format("{}|{:a},{:a},{:a}", texture, tint.r, tint.g, tint.b);
}

// The maps being prepared ahead, by key. A key prefetched twice (two bodies with the same map and
// tint) holds one future per request, taken in order.
struct PrefetchStore {
    std::mutex mutex;
    std::multimap<std::string, std::future<BodyMap>> pending;
};

PrefetchStore& store() {
    static PrefetchStore s;
    return s;
}

}  // namespace

BodyMap prepare_body_map(const std::string& texture, const glm::dvec3& tint) {
    BodyMap m;
    m.image = load_body_image(texture);
    m.mips = box_filter_mip_chain(m.image.width, m.image.height, m.image.rgb);
    m.mean_rgb = tint * body_map_mean_rgb(m.image);
    m.grid = luminance_grid(m.image.width, m.image.height, m.image.rgb, tint);
    return m;
}

std::thread prefetch_body_maps(const SceneConfig& scene) {
    std::vector<std::pair<std::string, glm::dvec3>> maps;
    for (const auto& b : scene.bodies)
        if (b.kind != BodyKind::Star) maps.emplace_back(b.texture, glm::dvec3(b.tint));
    if (scene.milky_way.present) maps.emplace_back(scene.milky_way.texture, glm::dvec3(1.0));
    auto tasks = std::make_shared<std::vector<std::packaged_task<BodyMap()>>>();
    {
        const std::lock_guard<std::mutex> lock(store().mutex);
        for (const auto& [texture, tint] : maps) {
            tasks->emplace_back([texture, tint] { return prepare_body_map(texture, tint); });
            store().pending.emplace(map_key(texture, tint), tasks->back().get_future());
        }
    }
    return std::thread([tasks] {
        for (auto& t : *tasks) t();
    });
}

BodyMap take_body_map(const std::string& texture, const glm::dvec3& tint) {
    std::future<BodyMap> ready;
    {
        const std::lock_guard<std::mutex> lock(store().mutex);
        const auto it = store().pending.find(map_key(texture, tint));
        if (it != store().pending.end()) {
            ready = std::move(it->second);
            store().pending.erase(it);
        }
    }
    return ready.valid() ? ready.get() : prepare_body_map(texture, tint);
}

}  // namespace cupola
