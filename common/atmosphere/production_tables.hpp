#pragma once
// Building, caching and loading the production atmosphere's tables (transmittance, multiple
// scattering, ground irradiance; see shaders/shared/atmosphere_tables.glsl for what a texel
// holds). Built on the CPU with threads by the shared shading code; cached on disk as 32-bit
// float EXR files through OpenImageIO, keyed by a hash of the atmosphere parameters and the
// table settings, so a parameter change can never reuse a stale table.
#include <cstddef>
#include <string>

#include "atmosphere/atmosphere_parameters.hpp"
#include "atmosphere/production_quality.hpp"
#include "shading/shared_shading.hpp"

namespace cupola::atmosphere {

struct ProductionTables {
    shading::Texture2DData transmittance;
    shading::Texture2DData multiple_scattering;
    shading::Texture2DData irradiance;
    double build_seconds = 0.0;  // 0 when loaded from the cache
    bool from_cache = false;
    std::string cache_key;  // hex; file names are <name>-<key>-<table>.exr

    std::size_t bytes() const;  // CPU memory of the three tables (RGBA32F)
};

struct TableCacheOptions {
    bool enabled = true;
    std::string directory;  // empty: default_table_cache_directory()
    int threads = 0;        // 0: hardware concurrency
};

// $CUPOLA_CACHE_DIR, else $XDG_CACHE_HOME/cupola/atmosphere, else $HOME/.cache/cupola/atmosphere,
// else ./.cupola-cache/atmosphere.
std::string default_table_cache_directory();

// Hash (hex) of everything the tables depend on: parameters, table settings, format version and
// the text of the shared shading code. `variant` names a table set of other sample wavelengths
// (the sky-view level's second triplet, production_model.hpp): "" for the first.
std::string table_cache_key(const AtmosphereParameters& p, const ProductionQuality& q, const std::string& variant = "");

// Computes the tables (no cache), with a progress bar labelled by the atmosphere name.
ProductionTables build_production_tables(const std::string& label, const shading::AtmosphereParams& gpu,
                                         const ProductionQuality& q, int threads);

// Loads the tables from the cache when present and valid, otherwise builds and stores them.
// A damaged cache file is logged and rebuilt; a cache directory that cannot be written is
// logged and the tables are used from memory.
ProductionTables load_or_build_tables(const AtmosphereParameters& p, const shading::AtmosphereParams& gpu,
                                      const ProductionQuality& q, const TableCacheOptions& cache,
                                      const std::string& variant = "");

}  // namespace cupola::atmosphere
