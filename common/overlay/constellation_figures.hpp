#pragma once
// The constellations as a planetarium draws them: stick figures, names and the IAU boundaries, from
// data/sky/constellations.json (derived from d3-celestial's data by tools/convert_constellations.py;
// provenance in data/sky/README.md). Directions are unit vectors in the world frame (ICRS/J2000
// equatorial axes, the frame of the snapshot's positions).
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cupola {

struct ConstellationLabel {
    std::string text;
    glm::dvec3 dir{0.0, 0.0, 1.0};
};

struct ConstellationFigure {
    std::string id;                                   // IAU abbreviation ("Ori")
    std::string name;                                 // "Orion"
    int rank = 1;                                     // 1: the most prominent figures .. 3
    std::vector<ConstellationLabel> labels;           // one, or one per part (Serpens)
    std::vector<std::vector<glm::dvec3>> lines;       // polylines: consecutive points are joined
    std::vector<std::vector<glm::dvec3>> boundaries;  // closed rings
};

// Unit vector of a right ascension and declination in degrees.
glm::dvec3 radec_deg_to_dir(double ra_deg, double dec_deg);

// Reads the file; throws std::runtime_error naming the file and the field (for example
// "constellations[12].lines[0][3]: right ascension 400 is outside [0, 360)") when it cannot be
// read or does not have that form.
std::vector<ConstellationFigure> load_constellation_figures(const std::string& file);
// The same from the text itself; `source` names it in errors.
std::vector<ConstellationFigure> parse_constellation_figures(const std::string& text, const std::string& source);

}  // namespace cupola
