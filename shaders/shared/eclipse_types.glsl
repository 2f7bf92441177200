// Plain data types of the shared eclipse code (shared by GLSL and C++; see atmosphere_types.glsl
// for why types live apart from the functions).

// Shadow modes (RenderSettings::flags carries one per frame, switchable at runtime). The only
// definition of the numbers: C++'s ShadowMode (common/config/scene_config.hpp) takes its values
// from these.
const int ECLIPSE_MODE_EXACT = 0;         // limb-darkened disc overlap, Gauss-Legendre in radius
const int ECLIPSE_MODE_FAST = 1;          // UniView's linear penumbra, Butterworth umbra edge
const int ECLIPSE_MODE_LUT = 2;           // 2D table: radius ratio x normalised separation
const int ECLIPSE_MODE_ILLUSTRATIVE = 3;  // umbra, antumbra and penumbra as uniform tints
const int ECLIPSE_MODE_OFF = 4;           // no shadows: the CPU sends no casters (count = 0)

const int ECLIPSE_MAX_CASTERS = 4;  // per receiver in one pass

// One caster seen from a receiver point, in units of the Sun's apparent (angular) radius.
struct EclipseDiscs {
    float ratio;           // a = occluder angular radius / Sun angular radius
    float separation;      // s = angle between the centres / Sun angular radius
    float sun_radius_rad;  // the Sun's angular radius
};

// Everything a pass needs to shadow one receiver: positions are relative to the receiver's
// centre in metres (differences taken in double on the CPU, then rounded to float), so a point
// on the receiver is just normal * radius and no large coordinate ever reaches the GPU.
struct EclipseCasters {
    int count;                // 0: nothing can shadow this receiver this frame (skip all work)
    int mode;                 // ECLIPSE_MODE_*
    float limb_u;             // the Sun's linear limb-darkening coefficient
    float butterworth_order;  // fast mode: sharpness n of the umbra edge
    vec3 sun_position_m;      // Sun centre
    float sun_radius_m;
    vec3 caster_position_m[ECLIPSE_MAX_CASTERS];  // caster centres
    float caster_radius_m[ECLIPSE_MAX_CASTERS];
    vec3 umbra_light[ECLIPSE_MAX_CASTERS];        // light left deep in the caster's umbra per unit
                                                  // sunlight (refraction through its atmosphere), rgb
};

// A straight path through a receiver's shadows (an atmosphere's view ray): the point at
// distance t_m along it is origin_m + dir * t_m, relative to the receiver's centre.
struct EclipseRay {
    EclipseCasters casters;
    vec2 lut_size;
    vec3 origin_m;
    vec3 dir;
};
