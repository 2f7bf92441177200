#pragma once
// One projector's calibration in the one form the warp pass (slave/output/warp_pass) and the
// checks use, whatever file it came from: an MPCDI region (common/calibration/mpcdi_package) or a
// Paul Bourke mesh (common/calibration/bourke_mesh). Every reading switch of those formats is
// resolved by the readers, so two files that mean the same calibration give equal ProjectorWarps.
//
// Conventions, fixed here for every consumer:
//  - Projector raster: raster_width x raster_height pixels, pixel (0,0) at the TOP left.
//  - Grid: `columns` x `rows` points in fill layout over the raster: point (i, j) sits at pixel
//    position ((i + 0.5) * raster_width / columns, (j + 0.5) * raster_height / rows), j = 0 is the
//    TOP row, stored row-major (index j * columns + i). Between points: bilinear.
//  - Content coordinates (u, v) in [0,1]: what the projector point shows, in the texture the warp
//    samples (the channel's frustum render for a 3d profile or a Bourke mesh, the whole buffer
//    content for a 2d profile): u right, v UP, origin at the content's bottom left (OpenGL UV).
//    A NaN u or v marks a point the projector does not show (black).
//  - intensity: per grid point blend factor (Bourke `i`), linear light; empty means 1 everywhere.
//  - alpha, beta maps: linear light in [0,1] (already decoded from the file's embedded gamma),
//    row 0 the TOP row, any size (resampled bilinearly onto the raster). Empty: alpha 1, beta 0.
//  - Blend: C_out = C * alpha * intensity * (1 - beta) + beta, in linear light, then encoded with
//    the projector's gamma: value = C_out^(1 / projector_gamma).
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "projection/channel_frustum.hpp"

namespace cupola {

// Raster position of grid point (i, j) in fill layout (above): the one formula of the contract.
inline glm::dvec2 grid_point_pixel(int i, int j, int columns, int rows, int raster_width, int raster_height) {
    return {(i + 0.5) * raster_width / columns, (j + 0.5) * raster_height / rows};
}

struct WarpGrid {
    int columns = 0;
    int rows = 0;
    std::vector<glm::dvec2> uv;    // columns * rows, row 0 at the top; NaN: not shown
    std::vector<float> intensity;  // columns * rows or empty (1)
};

struct BlendMap {
    int width = 0;
    int height = 0;
    std::vector<float> value;  // width * height, linear, row 0 at the top; empty map: not given

    bool empty() const { return value.empty(); }
};

// A projector frustum as MPCDI's 3d profile gives it, converted to the channel's orientation and
// its four half-angles (common/projection/channel_frustum.hpp): it can define the channel.
struct CalibratedFrustum {
    EulerDeg orientation;
    FovDeg fov;
};

struct ProjectorWarp {
    std::string source;     // "FILE region ID" or "FILE": named in every error about it
    std::string region_id;  // MPCDI region id; empty for a Bourke mesh
    int raster_width = 0;   // projector pixels
    int raster_height = 0;
    WarpGrid grid;
    BlendMap alpha;  // empty: 1
    BlendMap beta;   // empty: 0
    double projector_gamma = 2.2;
    std::optional<CalibratedFrustum> frustum;  // 3d profile only
};

}  // namespace cupola
