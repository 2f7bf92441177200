#pragma once
// Reads an MPCDI package (VESA MPCDI v2.0 (2015)): the zip (libzip), its mpcdi.xml (pugixml) and
// the PFM warps and PNG blend maps (OpenImageIO) of every region, into ProjectorWarps
// (calibration/projector_warp.hpp) under the reading switches of calibration/mpcdi_reading.hpp.
// Profiles 2d and 3d, geometry levels 1 and 2, colour levels 1 and 2; v2.0's profile/geometry/
// color attributes or v1's single `level`; attribute names case-insensitive (§3.5.2).
#include <optional>
#include <string>
#include <vector>

#include "calibration/mpcdi_reading.hpp"
#include "calibration/projector_warp.hpp"

namespace cupola {

struct MpcdiFileRef {
    std::string path;                   // inside the package
    int component_depth = 1;            // 1 | 3
    int bit_depth = 8;                  // 8 | 16
    double gamma_embedded = 1.0;        // alpha: linear = stored^gamma_embedded (§2.5.1.2.4)
    bool gamma_embedded_given = false;  // also the projector's gamma (PyMPCDI's targetGamma)
    bool given = false;
};

struct MpcdiRegionInfo {
    std::string buffer_id;
    int buffer_width = 0;
    int buffer_height = 0;
    std::string id;
    double x = 0.0, y = 0.0, x_size = 1.0, y_size = 1.0;  // normalized placement in the buffer
    int x_resolution = 0;                                 // projector raster
    int y_resolution = 0;
    std::optional<CalibratedFrustum> frustum;  // 3d profile
    MpcdiFileRef warp_file, alpha_map, beta_map;
};

class MpcdiPackage {
public:
    // Reads the zip's entries and parses mpcdi.xml; throws CalibrationError naming file and field.
    static MpcdiPackage open(const std::string& file);
    // The same from bytes in memory (`name` is named in errors).
    static MpcdiPackage from_bytes(const std::string& bytes, const std::string& name);

    const std::string& name() const { return name_; }
    const std::string& profile() const { return profile_; }
    int geometry_level() const { return geometry_level_; }
    int color_level() const { return color_level_; }
    const std::vector<MpcdiRegionInfo>& regions() const { return regions_; }  // in file order

    // One region's warp and blend, resolved under `reading`; throws CalibrationError.
    ProjectorWarp read_region(const std::string& region_id, const MpcdiReading& reading = {}) const;

private:
    std::string name_;
    std::string profile_;
    int geometry_level_ = 1;
    int color_level_ = 1;
    std::vector<MpcdiRegionInfo> regions_;
    std::string zip_bytes_;  // the package; entries are read from it when a region is read

    std::string entry(const std::string& path, const std::string& field) const;
    friend struct MpcdiPackageParser;
};

}  // namespace cupola
