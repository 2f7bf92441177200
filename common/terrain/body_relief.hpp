#pragma once
// A body's relief from its scene configuration (config/scene_config.hpp, TerrainConfig): the
// elevation file through GDAL when there is one, procedural relief above its resolution and
// where it has none. A file that cannot be read (corrupt, not a raster, the wrong coordinates)
// does not stop the show: the relief falls back to procedural alone, and why is kept to report.
#include <memory>
#include <string>

#include "config/scene_config.hpp"
#include "terrain/relief.hpp"

namespace cupola::terrain {

struct BodyRelief {
    std::shared_ptr<const Relief> relief;
    std::string fallback;  // empty, or why the elevation file was not used (naming it)
};

ProceduralRelief procedural_relief_of(const TerrainConfig& terrain);
BodyRelief open_body_relief(const BodyConfig& body);

}  // namespace cupola::terrain
