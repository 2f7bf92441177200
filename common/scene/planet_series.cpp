#include "scene/planet_series.hpp"

#include <erfa.h>
#include <erfam.h>
#include <libnova/libnova.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace cupola {

namespace {

constexpr double kNodeSpacing_days = 0.25;
constexpr size_t kPlanets = 8;
constexpr size_t kCachedNodes = 8;  // per planet, direct-mapped by node index

using SeriesFunction = void (*)(double, ln_helio_posn*);

SeriesFunction series_function(PlanetSeries p) {
    static const std::array<SeriesFunction, kPlanets> f = {ln_get_mercury_helio_coords, ln_get_venus_helio_coords,
                                                           ln_get_mars_helio_coords,    ln_get_jupiter_helio_coords,
                                                           ln_get_saturn_helio_coords,  ln_get_uranus_helio_coords,
                                                           ln_get_neptune_helio_coords, ln_get_pluto_helio_coords};
    return f[static_cast<size_t>(p)];
}

// Spherical J2000 ecliptic (degrees, AU) to rectangular ICRS axes.
glm::dvec3 ecliptic_j2000_to_icrs(const ln_helio_posn& h) {
    static const double eps = eraObl06(ERFA_DJ00, 0.0);
    const double l = h.L * ERFA_DD2R, b = h.B * ERFA_DD2R;
    const glm::dvec3 e(h.R * std::cos(b) * std::cos(l), h.R * std::cos(b) * std::sin(l), h.R * std::sin(b));
    return {e.x, e.y * std::cos(eps) - e.z * std::sin(eps), e.y * std::sin(eps) + e.z * std::cos(eps)};
}

struct NodeCache {
    std::array<long long, kCachedNodes> index;
    std::array<glm::dvec3, kCachedNodes> position;
    NodeCache() { index.fill(std::numeric_limits<long long>::min()); }
};

glm::dvec3 node_position(PlanetSeries planet, long long node) {
    thread_local std::array<NodeCache, kPlanets> caches;
    NodeCache& c = caches[static_cast<size_t>(planet)];
    const size_t slot = static_cast<size_t>(node & static_cast<long long>(kCachedNodes - 1));
    if (c.index[slot] != node) {
        c.index[slot] = node;
        c.position[slot] = planet_heliocentric_series_au(planet, static_cast<double>(node) * kNodeSpacing_days);
    }
    return c.position[slot];
}

}  // namespace

PlanetSeries planet_series_from_name(const std::string& name) {
    static const std::array<const char*, kPlanets> names = {"mercury", "venus",  "mars",    "jupiter",
                                                            "saturn",  "uranus", "neptune", "pluto"};
    for (size_t i = 0; i < names.size(); ++i)
        if (name == names[i]) return static_cast<PlanetSeries>(i);
    throw std::invalid_argument("no planet series for '" + name + "' (mercury ... neptune, pluto)");
}

glm::dvec3 planet_heliocentric_series_au(PlanetSeries planet, double d) {
    ln_helio_posn h{};
    series_function(planet)(ERFA_DJ00 + d, &h);
    return ecliptic_j2000_to_icrs(h);
}

glm::dvec3 planet_heliocentric_au(PlanetSeries planet, double d) {
    // Cubic Lagrange interpolation through the nodes n-1, n, n+1, n+2 around d.
    const double x = d / kNodeSpacing_days;
    const long long n = static_cast<long long>(std::floor(x));
    const double u = x - static_cast<double>(n);  // in [0, 1)
    const double w0 = -u * (u - 1.0) * (u - 2.0) / 6.0, w1 = (u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0,
                 w2 = -(u + 1.0) * u * (u - 2.0) / 2.0, w3 = (u + 1.0) * u * (u - 1.0) / 6.0;
    return w0 * node_position(planet, n - 1) + w1 * node_position(planet, n) + w2 * node_position(planet, n + 1) +
           w3 * node_position(planet, n + 2);
}

}  // namespace cupola
