#pragma once
// The compact bright-star catalogue (data/stars/bright_stars.csv, made by tools/make_star_catalog.py).
// Positions are J2000/ICRS equatorial; the world frame has x toward RA 0h Dec 0, z toward the
// north celestial pole (y toward RA 6h).
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace cupola {

struct Star {
    double ra_rad = 0.0;
    double dec_rad = 0.0;
    float v_mag = 0.0f;
    float b_minus_v = 0.0f;
    std::string name;  // may be empty

    // Unit direction in the world frame.
    glm::dvec3 direction() const;
};

// Unit world-frame direction of an equatorial position.
glm::dvec3 equatorial_direction(double ra_rad, double dec_rad);

// Loads every star with v_mag <= magnitude_limit. Throws std::runtime_error naming the file (and
// "file:line" for a malformed line: wrong column count, non-numeric or out-of-range value).
std::vector<Star> load_star_catalog(const std::string& file, double magnitude_limit = 99.0);

}  // namespace cupola
