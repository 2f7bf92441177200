#include "atmosphere/production_tables.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <thread>
#include <vector>

#include "image/table_file.hpp"
#include "shading/shader_sources.hpp"
#include "util/progress_bar.hpp"

namespace cupola::atmosphere {
namespace fs = std::filesystem;
using shading::Texture2DData;

namespace {
constexpr const char* kTableFormatVersion = "cupola-atmosphere-tables-v1";

Texture2DData make_table(int w, int h) {
    Texture2DData t;
    t.width = w;
    t.height = h;
    t.texels.assign(static_cast<size_t>(w) * h, glm::vec4(0.0f));
    return t;
}

// Fills every texel of t with fn(u, v) (texel-centre coordinates), rows spread over threads.
void fill_table4(Texture2DData& t, int threads, ProgressBar& bar, const std::function<glm::vec4(glm::vec2)>& fn) {
    std::atomic<int> next_row{0};
    auto worker = [&] {
        for (int y = next_row++; y < t.height; y = next_row++) {
            for (int x = 0; x < t.width; ++x) {
                const glm::vec2 uv((x + 0.5f) / t.width, (y + 0.5f) / t.height);
                t.texels[static_cast<size_t>(y) * t.width + x] = fn(uv);
            }
            bar.advance(t.width);
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
}

// The same for a three-channel fn; alpha 1.
void fill_table(Texture2DData& t, int threads, ProgressBar& bar, const std::function<glm::vec3(glm::vec2)>& fn) {
    fill_table4(t, threads, bar, [&](glm::vec2 uv) { return glm::vec4(fn(uv), 1.0f); });
}

int resolve_threads(int threads) {
    if (threads > 0) return threads;
    const unsigned hw = std::thread::hardware_concurrency();
    return hw == 0 ? 1 : static_cast<int>(hw);
}

// The multiple-scattering table: J_2 (atm_compute_ms), orders 3..ms_orders each from the previous
// order's table, summed; alpha the Rayleigh anisotropy ratio (the second order's P2 moment over
// the summed orders, atm_ms_rayleigh_factor), or 0 (isotropic) without ms_rayleigh_anisotropy.
void build_ms_table(Texture2DData& ms, const shading::AtmosphereParams& a, const shading::sampler2D& trans,
                    glm::vec2 trans_size, const ProductionQuality& q, int threads, ProgressBar& bar) {
    using namespace cupola::shading;
    const vec2 ms_size(ms.width, ms.height);
    fill_table4(ms, threads, bar, [&](vec2 uv) {
        const vec2 rs = atm_ms_r_mu_s(a, uv, ms_size);
        return atm_compute_ms(a, trans, trans_size, rs.x, rs.y, q.ms_directions, q.ms_steps, q.ms_orders == 0);
    });
    const int order_directions = q.ms_order_directions > 0 ? q.ms_order_directions : q.ms_directions;
    Texture2DData order = ms;
    for (int n = 3; n <= q.ms_orders; ++n) {
        Texture2DData next = make_table(ms.width, ms.height);
        const sampler2D prev{&order};
        fill_table(next, threads, bar, [&](vec2 uv) {
            const vec2 rs = atm_ms_r_mu_s(a, uv, ms_size);
            return atm_compute_ms_next_order(a, prev, ms_size, rs.x, rs.y, order_directions, q.ms_steps);
        });
        for (size_t i = 0; i < next.texels.size(); ++i) ms.texels[i] += glm::vec4(glm::vec3(next.texels[i]), 0.0f);
        order = std::move(next);
    }
    for (auto& v : ms.texels) v.w = q.ms_rayleigh_anisotropy && v.y > 0.0f ? v.w / v.y : 0.0f;
}
}  // namespace

std::size_t ProductionTables::bytes() const {
    return (transmittance.texels.size() + multiple_scattering.texels.size() + irradiance.texels.size()) *
           sizeof(glm::vec4);
}

std::string default_table_cache_directory() { return cache_directory("atmosphere"); }

std::string table_cache_key(const AtmosphereParameters& p, const ProductionQuality& q, const std::string& variant) {
    // The texts of the shared code that computes the tables are part of the key: a change to the
    // model's code can never reuse tables the old code built.
    std::string text = std::string(kTableFormatVersion) + "|" + p.hash_hex() + "|" + q.table_key() + "|" + variant;
    for (const char* f : kSharedShadingFiles) text += shader_source(f);
    return cache_key_hex(text);
}

ProductionTables build_production_tables(const std::string& label, const shading::AtmosphereParams& a,
                                         const ProductionQuality& q, int threads) {
    using namespace cupola::shading;
    const auto start = std::chrono::steady_clock::now();
    threads = resolve_threads(threads);
    ProductionTables t;
    if (q.analytic) {  // the fast mode samples no table; keep 1x1 placeholders for the GPU bindings
        t.transmittance = make_table(1, 1);
        t.multiple_scattering = make_table(1, 1);
        t.irradiance = make_table(1, 1);
        return t;
    }
    t.transmittance = make_table(q.transmittance_width, q.transmittance_height);
    t.multiple_scattering = make_table(q.ms_size, q.ms_size);
    t.irradiance = make_table(q.irradiance_width, q.irradiance_height);
    if (!q.multiple_scattering) t.multiple_scattering = make_table(1, 1);
    const long ms_passes = q.multiple_scattering ? std::max(1, q.ms_orders - 1) : 1;
    const long texels = static_cast<long>(t.transmittance.texels.size() +
                                          ms_passes * t.multiple_scattering.texels.size() + t.irradiance.texels.size());
    ProgressBar bar("atmosphere tables " + label, texels);
    const vec2 ts(t.transmittance.width, t.transmittance.height);
    const vec2 ms_size(t.multiple_scattering.width, t.multiple_scattering.height);
    const vec2 es(t.irradiance.width, t.irradiance.height);
    fill_table(t.transmittance, threads, bar, [&](vec2 uv) {
        const vec2 rm = atm_transmittance_r_mu(a, uv, ts);
        return atm_compute_transmittance(a, rm.x, rm.y, q.transmittance_steps);
    });
    const sampler2D trans{&t.transmittance};
    if (q.multiple_scattering) {
        build_ms_table(t.multiple_scattering, a, trans, ts, q, threads, bar);
    } else {
        bar.advance(1);
    }
    const sampler2D ms{&t.multiple_scattering};
    fill_table(t.irradiance, threads, bar, [&](vec2 uv) {
        const vec2 rs = atm_ms_r_mu_s(a, uv, es);
        return atm_compute_irradiance(a, trans, ts, ms, ms_size, q.multiple_scattering, rs.x, rs.y,
                                      q.irradiance_directions, q.irradiance_samples);
    });
    bar.finish();
    t.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return t;
}

ProductionTables load_or_build_tables(const AtmosphereParameters& p, const shading::AtmosphereParams& gpu,
                                      const ProductionQuality& q, const TableCacheOptions& cache,
                                      const std::string& variant) {
    const std::string key = table_cache_key(p, q, variant);
    const fs::path dir =
        cache.directory.empty() ? fs::path(default_table_cache_directory()) : fs::path(cache.directory);
    const std::string stem = (p.name.empty() ? std::string("atmosphere") : p.name) + "-" + key;
    const fs::path files[3] = {dir / (stem + "-transmittance.exr"), dir / (stem + "-multiple-scattering.exr"),
                               dir / (stem + "-irradiance.exr")};
    if (cache.enabled && !q.analytic && fs::exists(files[0]) && fs::exists(files[1]) && fs::exists(files[2])) {
        ProductionTables t;
        const int ms = q.multiple_scattering ? q.ms_size : 1;
        std::string why;
        if (read_table_file(files[0], q.transmittance_width, q.transmittance_height, kTableFormatVersion,
                            t.transmittance, why) &&
            read_table_file(files[1], ms, ms, kTableFormatVersion, t.multiple_scattering, why) &&
            read_table_file(files[2], q.irradiance_width, q.irradiance_height, kTableFormatVersion, t.irradiance,
                            why)) {
            t.from_cache = true;
            t.cache_key = key;
            spdlog::info("atmosphere {}: tables loaded from cache {}", p.name, (dir / stem).string());
            return t;
        }
        spdlog::warn("atmosphere {}: cached tables {} are unusable ({}); rebuilding", p.name, (dir / stem).string(),
                     why);
    }
    ProductionTables t = build_production_tables(p.name, gpu, q, cache.threads);
    t.cache_key = key;
    spdlog::info("atmosphere {} ({}): tables built in {:.3f} s, {} KiB", p.name, q.name, t.build_seconds,
                 t.bytes() / 1024);
    if (cache.enabled && !q.analytic) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        bool ok = !ec;
        ok = ok && write_table_file(files[0], t.transmittance, kTableFormatVersion);
        ok = ok && write_table_file(files[1], t.multiple_scattering, kTableFormatVersion);
        ok = ok && write_table_file(files[2], t.irradiance, kTableFormatVersion);
        if (!ok) spdlog::warn("atmosphere {}: could not write the table cache in {}", p.name, dir.string());
    }
    return t;
}

}  // namespace cupola::atmosphere
