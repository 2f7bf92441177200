// Plain data types of the shared atmosphere code (shared by GLSL and C++). Kept apart from the
// functions because in C++ the functions have internal linkage (see glsl_compat.hpp) while these
// types must be one type across translation units.

// Atmosphere description and local optical properties for the production model (shared by GLSL
// and C++). Three sample wavelengths per vec3 (x = 680 nm, y = 550 nm, z = 440 nm); lengths in
// metres, coefficients in m^-1 at density 1. Filled from AtmosphereParameters on the CPU
// (common/atmosphere/production_model.cpp), set as a uniform struct on the GPU.
struct AtmosphereParams {
    float bottom_radius_m;
    float top_radius_m;
    vec3 rayleigh_scattering_per_m;
    float rayleigh_scale_height_m;
    vec3 mie_scattering_per_m;
    vec3 mie_extinction_per_m;
    float mie_scale_height_m;
    float mie_g;
    vec3 ozone_absorption_per_m;  // at the tent peak
    float ozone_bottom_m;
    float ozone_peak_m;
    float ozone_top_m;
    vec3 ground_albedo;
};

// The atmospheric part of a camera ray. The camera sits at distance d from the planet centre,
// looking along the unit v; c_hat is the unit direction from the camera to the centre and sun the
// unit direction to the Sun (all in one frame; the CPU computes d and c_hat in double). Only
// angles and ratios enter, never positions, so the result stays exact in float for a camera 1 AU
// away (a float position there steps by 16 km): the entry point is located from the ray's closest approach
// to the centre, not by subtracting large distances.
struct AtmosphereRayStart {
    float r_m;       // radius of the start (the camera, or the entry into the top sphere)
    float mu;        // view zenith cosine there
    float mu_s;      // sun zenith cosine there
    float nu;        // cos(view, sun)
    float offset_m;  // distance from the camera to the start
    bool valid;      // false: the ray never enters the atmosphere
};

// Radiance per unit solar irradiance (hence per sr) scattered once toward a point with an
// isotropic phase, arriving from direction (mu, nu) [Hillaire's L'], and the transfer factor f_ms
// along it.
// Returned as (L.xyz, f.x..) packed in two vec3s through a struct.
struct AtmosphereMsTerms {
    vec3 second_order_per_sr;
    vec3 transfer;
};

struct AtmosphereSegment {
    vec3 inscatter_per_sr;  // radiance per unit solar irradiance
    vec3 transmittance;     // along the marched part of the ray
};

// The same with the in-scatter kept in its parts, for the sky-view table (atmosphere_sky_view.glsl),
// which applies the phase functions per pixel: single Rayleigh and single Mie scattering without
// their phase functions (times atm_rayleigh_phase / atm_cornette_shanks_phase of the pixel's nu
// they give radiance per unit solar irradiance) and the multiple scattering (isotropic, radiance).
struct AtmosphereSplitSegment {
    vec3 rayleigh_unphased;
    vec3 mie_unphased;
    vec3 multiple_per_sr;
    vec3 transmittance;
};

// The same three parts before colour: per unit solar irradiance at one triplet's sample
// wavelengths (third: the transmittance, sky half, or the white ground's radiance, ground half).
struct AtmosphereSkyViewSamples {
    vec3 phased;
    vec3 mie;
    vec3 third;
};

// One texel of the sky-view table (atmosphere_sky_view.glsl): its three parts, linear sRGB.
struct AtmosphereSkyViewTexel {
    vec3 phased;  // single Rayleigh with its phase, plus multiple scattering
    vec3 mie;     // single Mie without its phase
    vec3 third;   // sky: effective transmittance; ground: the white ground's radiance
};

// What a draw of something beyond the air (a star, the Sun, a moon) needs to take the air in
// front of it from the sky-view table, with the camera inside the atmosphere and the sky drawn
// before it (atmosphere_sky_view.glsl, atm_sky_in_front_*). Directions in the channel frame.
struct SkyInFront {
    vec3 up;            // unit, planet centre -> camera
    float r_m;          // the camera's distance from the centre (at least the ground's + 1 m)
    float mu_h;         // the ground horizon's zenith cosine at the camera
    vec3 sun;           // unit, planet centre -> Sun
    vec3 sun_perp;      // atm_sky_view_sun_perp(up, sun)
    vec2 size;          // the table's size in texels
    float solar_scale;  // the scene's solar irradiance over that of the model's physical spectrum
    vec3 moon;          // unit, camera -> Moon (common/atmosphere/moonlit_sky.hpp)
    vec3 moon_perp;     // atm_sky_view_sun_perp(up, moon)
    vec3 moon_scale;    // its irradiance over the Sun's per channel, times solar_scale; 0: no moonlit sky
};

struct AtmosphereAnalyticFit {
    vec3 k1_rad;
    float k2;
};
