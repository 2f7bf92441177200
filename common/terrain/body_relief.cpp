#include "terrain/body_relief.hpp"

#include <exception>

namespace cupola::terrain {

ProceduralRelief procedural_relief_of(const TerrainConfig& t) {
    ProceduralRelief p;
    p.base_wavelength_m = t.procedural_wavelength_m;
    p.base_amplitude_m = t.procedural_amplitude_m;
    p.gain = t.procedural_gain;
    p.octaves = t.procedural_octaves;
    p.seed = t.seed;
    return p;
}

BodyRelief open_body_relief(const BodyConfig& body) {
    BodyRelief out;
    const ProceduralRelief procedural = procedural_relief_of(body.terrain);
    std::shared_ptr<const ElevationRaster> data;
    if (!body.terrain.elevation.empty()) {
        try {
            data = std::make_shared<const ElevationRaster>(body.terrain.elevation);
        } catch (const std::exception& e) {
            out.fallback = body.name + " terrain: " + e.what() + "; drawing procedural relief instead";
        }
    }
    out.relief = std::make_shared<const Relief>(body.radius_m, data, procedural);
    return out;
}

}  // namespace cupola::terrain
