#pragma once
// Ray-sphere geometry of a spherical atmosphere in the (r, mu) parametrisation: r is the distance
// of the ray origin from the planet centre (m), mu the cosine of the ray's zenith angle there.
// All functions are double precision, total (no NaN for any finite input) and clamp their results:
// discriminants are formed as R^2 - r^2 (1 - mu)(1 + mu) (no r^2 mu^2 - r^2 cancellation) and
// clamped at 0, distances at 0.
namespace cupola::atmosphere {

// The smallest camera altitude the integrator accepts (m); cameras below are raised to it
// (a camera exactly at or inside the ground would otherwise give empty or negative paths).
inline constexpr double kMinCameraAltitude = 1.0;

// r^2 (mu^2 - 1) + radius^2, computed without cancellation (may be negative: no intersection).
double sphere_discriminant(double r, double mu, double radius);

// Distance along the ray to the far intersection with the sphere of radius top (the exit, for an
// origin inside); 0 when there is none.
double distance_to_top(double r, double mu, double top);

// Distance along the ray to the near intersection with the sphere of radius bottom; 0 when the ray
// misses it (callers should decide with ray_hits_ground first).
double distance_to_ground(double r, double mu, double bottom);

// Cosine of the zenith angle of the horizon seen from r: -sqrt(1 - (bottom/r)^2), 0 for r <= bottom.
double mu_horizon(double r, double bottom);

// True when the ray from r with cosine mu meets the ground sphere: mu < mu_horizon(r, bottom).
// A ray exactly at the horizon grazes and does not hit.
bool ray_hits_ground(double r, double mu, double bottom);

// Distance to whichever boundary the ray from inside the shell [bottom, top] meets first.
double distance_to_nearest_boundary(double r, double mu, double bottom, double top);

// Result of bringing a camera that may be outside the atmosphere to the start of its ray's
// atmospheric part.
struct RayEntry {
    bool intersects = false;  // false: the ray never enters the atmosphere
    double offset = 0.0;      // distance from the camera to the start (0 for a camera inside)
    double r = 0.0;           // start radius (== top for a camera outside)
    double mu = 0.0;          // cosine of the zenith angle at the start
};
// r is first clamped to bottom + kMinCameraAltitude. For r > top the origin is moved explicitly to
// the entry point on the top sphere (no reliance on NaN from a negative square root).
RayEntry enter_atmosphere(double r, double mu, double bottom, double top);

}  // namespace cupola::atmosphere
