#pragma once
// The stored atmosphere reference dataset (data/atmosphere/<body>_reference.csv): the CPU
// reference integrator evaluated on validation_set(), written by tools/atmosphere_reference and
// read back by the tests that measure the production models against it.
//
// FORMAT (CSV, one query per row, in validation_set() order):
//   * Leading comment lines start with '#'. Those of the form "# key=value" (key made of
//     [a-z0-9_]) are metadata; preset, hash (AtmosphereParameters::hash_hex()), orders, paths,
//     seed and directions are required (the ReferenceSettings used, everything else at its
//     default), command and date record how and when the file was made. Other comments are free
//     text.
//   * Then the header line kReferenceCsvHeader.
//   * Then the rows: camera, altitude_m, view_zenith_deg, sun_zenith_deg, relative_azimuth_deg
//     (printed with %.17g: they round-trip exactly, so a row's query can be recomputed bit for
//     bit), hits_ground and in_atmosphere (0/1), luminance and luminance_stderr (cd m^-2; the
//     stderr is that of the Monte Carlo part, orders >= 2), r, g, b (linear sRGB, photometric
//     scale) and x, y, z (CIE 1931, y = luminance), printed with %.9g.
// Empty lines are ignored. Anything else malformed makes the reader throw std::runtime_error
// "<file>:<line>: <what>".
#include <glm/glm.hpp>

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "atmosphere/reference_integrator.hpp"
#include "atmosphere/validation_set.hpp"

namespace cupola::atmosphere {

inline constexpr const char* kReferenceCsvHeader =
    "camera,altitude_m,view_zenith_deg,sun_zenith_deg,relative_azimuth_deg,hits_ground,in_atmosphere,"
    "luminance,luminance_stderr,r,g,b,x,y,z";

struct ReferenceRow {
    ValidationCase c;
    bool hits_ground = false, in_atmosphere = true;
    double luminance = 0.0, luminance_stderr = 0.0;
    glm::dvec3 rgb{0.0}, xyz{0.0};
};

struct ReferenceDataset {
    std::string preset, hash;
    int orders = 0, paths = 0;
    std::uint64_t seed = 0;
    int directions = 0;                           // directions_per_set of validation_set()
    std::map<std::string, std::string> metadata;  // every "# key=value" line, the required ones included
    std::vector<ReferenceRow> rows;
};

// The ReferenceSettings the rows at this sun zenith were computed with, from the metadata: orders,
// paths and seed, and the optional ms_estimator (lit_segment or collision; absent: collision, the
// only estimator before the line sample), ms_max_paths, ms_target_noise and ms_target_floor
// (absent: a fixed path count). A file whose rows were recomputed only for some sun zenith angles
// lists them in recomputed_sun_zenith_deg (comma-separated); its other rows were kept from an
// earlier file, whose settings are the same keys prefixed "kept_". Everything else is at its
// default. Throws std::runtime_error naming the key whose value is malformed.
ReferenceSettings row_settings(const ReferenceDataset& d, double sun_zenith_deg);

// A row as the tool stores it: the query and what ReferenceIntegrator::sky() returned for it.
ReferenceRow make_reference_row(const ValidationCase& c, const SkyRadiance& s);

// Writes the metadata (the required keys from the fields, then the other entries of `metadata`),
// free-text `comments` (each written as "# " + line), the header and the rows.
void write_reference_dataset(std::ostream& out, const ReferenceDataset& d,
                             const std::vector<std::string>& comments = {});

ReferenceDataset read_reference_dataset(std::istream& in, const std::string& name);
ReferenceDataset read_reference_dataset(const std::string& path);

}  // namespace cupola::atmosphere
