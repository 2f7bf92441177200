#pragma once
// A body's relief: elevation data where there is some (ElevationRaster), procedural detail above
// the data's resolution (the octaves shorter than two data samples), procedural relief alone
// where there is no data (outside its extent, at no-data samples, or no file). Deterministic from the position, so
// every node of a cluster builds the same tiles.
#include <glm/glm.hpp>

#include <memory>
#include <string>

#include "terrain/elevation_raster.hpp"
#include "terrain/procedural_relief.hpp"

namespace cupola::terrain {

class Relief {
public:
    // data may be null (procedural relief alone).
    Relief(double radius_m, std::shared_ptr<const ElevationRaster> data, const ProceduralRelief& procedural);

    // The height (m) above the reference sphere in a unit direction, for a mesh of sample
    // spacing spacing_m (0: the finest the relief has).
    double height_m(const glm::dvec3& dir, double spacing_m) const;
    // A bound on the height error of a mesh of spacing h against the finest mesh of the relief
    // (Sperlhofer 2011 and Schafhitzel et al. 2007 refine by such an error: Roettger et al. 1998's
    // criterion, the error over the distance). The data's part is its steepest rise times h
    // (bilinear interpolation of a function of bounded slope), the procedural part as
    // ProceduralRelief::mesh_error_m.
    double mesh_error_m(double spacing_m) const;
    // Every height lies within [min_height_m, max_height_m].
    double min_height_m() const { return min_m_; }
    double max_height_m() const { return max_m_; }
    double radius_m() const { return radius_m_; }
    bool has_data() const { return data_ != nullptr; }
    // Whether the data gives the height in this direction (false without data, outside its
    // extent, or next to a no-data sample): where it does not, the procedural relief is whole.
    bool data_covers(const glm::dvec3& dir) const;
    const ElevationRaster* data() const { return data_.get(); }

private:
    double radius_m_;
    std::shared_ptr<const ElevationRaster> data_;
    ProceduralRelief procedural_;
    double detail_below_m_ = 0.0;  // procedural octaves shorter than this (0: all of them)
    double min_m_ = 0.0, max_m_ = 0.0;
};

}  // namespace cupola::terrain
