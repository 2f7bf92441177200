#include "glare/analytic_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shading/shared_shading.hpp"

namespace cupola {

namespace {

constexpr double kPi = std::numbers::pi;

// Angular radius of a sphere of radius r at distance d > r: asin(r / d), through atan2 so that it
// stays exact near pi / 2 (a camera just above a planet: r / d = 1 - 3e-7).
double angular_radius(double r, double d) { return std::atan2(r, std::sqrt((d - r) * (d + r))); }

// alpha - sin(alpha) cos(alpha) = (x - sin x) / 2, x = 2 alpha: the area of a circular segment of
// half-angle alpha (central angle 2 alpha) of the unit circle. Series below x = 0.1, where
// x - sin x would cancel (truncation ~x^11 / 4e7, relative 1e-15).
double segment_area_unit(double alpha) {
    const double x = 2.0 * alpha;
    if (x < 0.1) {
        const double x2 = x * x;
        return 0.5 * x * x2 * (1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0 - x2 / 362880.0)));
    }
    return 0.5 * (x - std::sin(x));
}

// Area and first moment of a hidden region about the source's centre along the direction to the
// occluder's centre (moment = area * centroid position on that line), angles in radians.
struct Hidden {
    double area = 0.0;
    double moment = 0.0;
};

// A segment of a circle of radius R with half-angle alpha: its area, and its centroid's distance
// from that circle's centre, 2 R sin^3 alpha / (3 (alpha - sin alpha cos alpha)).
void segment(double R, double alpha, double& area, double& centroid) {
    const double g = segment_area_unit(alpha);
    const double s = std::sin(alpha);
    area = R * R * g;
    centroid = g > 0.0 ? 2.0 * R * s * s * s / (3.0 * g) : R;
}

// The lens where the source disc (radius sigma, at 0) and the occluder's disc (radius rho, at
// theta along the line of centres) overlap, flat in the tangent plane: the source's segment beyond
// the radical line plus the occluder's segment on the source's side of it.
Hidden lens(double sigma, double rho, double theta) {
    if (theta >= sigma + rho) return {};
    if (rho >= sigma + theta) return {kPi * sigma * sigma, 0.0};  // source wholly behind the occluder
    if (sigma >= rho + theta) {                                   // occluder wholly on the disc
        const double a = kPi * rho * rho;
        return {a, a * theta};
    }
    // Half-chord at the radical line from the triangle (sigma, rho, theta): Kahan's area formula
    // (sides sorted p >= q >= r), well conditioned for slivers; the radical line's distances from
    // both centres each without cancellation of nearly equal squares.
    double p = sigma, q = rho, r = theta;
    if (p < q) std::swap(p, q);
    if (q < r) std::swap(q, r);
    if (p < q) std::swap(p, q);
    const double four_area = std::sqrt(std::max((p + (q + r)) * (r - (p - q)) * (r + (p - q)) * (p + (q - r)), 0.0));
    const double y0 = 0.5 * four_area / theta;
    const double x_source = ((sigma - rho) * (sigma + rho) + theta * theta) / (2.0 * theta);
    const double x_occluder = ((rho - sigma) * (rho + sigma) + theta * theta) / (2.0 * theta);
    double a1 = 0.0, c1 = 0.0, a2 = 0.0, c2 = 0.0;
    segment(sigma, std::atan2(y0, x_source), a1, c1);  // the source's, centroid at +c1
    segment(rho, std::atan2(y0, x_occluder), a2, c2);  // the occluder's, centroid at theta - c2
    return {a1 + a2, a1 * c1 + a2 * (theta - c2)};
}

// Straight-edge limit: the occluder's limb is a line across the source disc at signed distance h
// from its centre (h > 0: the centre is visible); hidden is the disc's segment beyond it.
Hidden straight_edge(double sigma, double h) {
    if (h >= sigma) return {};
    if (h <= -sigma) return {kPi * sigma * sigma, 0.0};
    double area = 0.0, centroid = 0.0;
    segment(sigma, std::atan2(std::sqrt((sigma - h) * (sigma + h)), h), area, centroid);
    return {area, area * centroid};
}

}  // namespace

GlareVisibility analytic_visibility(const glm::dvec3& camera_m, const glm::dvec3& source_center_m,
                                    double source_radius_m, const std::vector<SphereOccluder>& occluders) {
    GlareVisibility out;
    const glm::dvec3 to_source = source_center_m - camera_m;
    const double ds = glm::length(to_source);
    const double source_r = std::max(source_radius_m, 0.0);
    if (!(ds > source_r)) return out;  // camera inside (or at) the source: out of scope, unoccluded
    const glm::dvec3 us = to_source / ds;
    const double sigma = angular_radius(source_r, ds);
    const double disc_area = kPi * sigma * sigma;

    double fraction = 1.0;
    double hidden_area = 0.0;
    glm::dvec3 moment(0.0);
    for (const SphereOccluder& occ : occluders) {
        const glm::dvec3 to_occluder = occ.center_m - camera_m;  // in double, before any float
        const double dc = glm::length(to_occluder);
        const double r = std::max(occ.radius_m, 0.0);
        if (dc <= r) return {0.0, glm::dvec3(0.0)};  // camera inside an occluder: nothing visible
        if (dc - r >= ds) continue;                  // near side beyond the source's centre
        const glm::dvec3 uc = to_occluder / dc;
        const double rho = angular_radius(r, dc);
        const double theta = std::atan2(glm::length(glm::cross(us, uc)), glm::dot(us, uc));
        if (theta >= rho + sigma) continue;  // discs apart (also every occluder behind the camera)
        if (sigma <= 0.0) {                  // point source: hidden or not
            fraction = 0.0;
            continue;
        }
        Hidden h;
        double f = 1.0;
        if (rho >= kStraightEdgeAngle || rho + sigma >= 0.5 * kPi) {
            // Huge occluder (the ground): straight-edge limit in double (see the header).
            h = straight_edge(sigma, theta - rho);
            f = 1.0 - h.area / disc_area;
        } else {
            const shading::EclipseDiscs d = shading::eclipse_discs(glm::vec3(to_source), static_cast<float>(source_r),
                                                                   glm::vec3(to_occluder), static_cast<float>(r));
            f = shading::eclipse_visible_exact(d.ratio, d.separation, 0.0f);
            h = lens(sigma, rho, theta);
        }
        fraction *= std::clamp(f, 0.0, 1.0);
        hidden_area += h.area;
        const glm::dvec3 perp = uc - glm::dot(uc, us) * us;  // toward the occluder, in the tangent plane
        const double perp_len = glm::length(perp);
        if (perp_len > 0.0 && h.moment != 0.0) moment += (h.moment / perp_len) * perp;
    }
    out.visible_fraction = std::clamp(fraction, 0.0, 1.0);
    const double visible_area = disc_area - hidden_area;  // lenses assumed not to overlap
    if (out.visible_fraction <= 0.0 || !(visible_area > 0.0)) return out;
    glm::dvec3 offset = -moment / visible_area;
    const double len = glm::length(offset);
    if (len > sigma) offset *= sigma / len;  // a centroid lies inside the disc (rounding guard)
    out.centroid_offset = offset;
    return out;
}

std::vector<SphereOccluder> snapshot_occluders(const Snapshot& snap, const SceneConfig& scene, uint16_t source_body_id,
                                               bool airless_only) {
    std::vector<SphereOccluder> out;
    for (const BodyState& st : snap.bodies) {
        if (st.id == source_body_id || st.id >= scene.bodies.size()) continue;
        const BodyConfig& body = scene.bodies[st.id];
        if (body.kind == BodyKind::Star || (airless_only && body.atmosphere.present)) continue;
        out.push_back({st.position_m, body.radius_m});
    }
    return out;
}

}  // namespace cupola
