#pragma once
// The night sky's own brightness at the zenith (airglow and light pollution) as a planetarium
// gives it: a surface brightness in V magnitudes per square arcsecond, or a Bortle class. The
// shading of the glow and its gradient toward the horizon are in shaders/shared/night_sky.glsl.
namespace cupola {

// Bortle (2001)'s nine classes of observing site, from 1 (an excellent dark site) to 9 (an inner
// city), with the zenith sky brightness (V mag/arcsec^2) commonly measured for each by sky-quality
// meters: the middle of each class's range, 22.0 for class 1 (the natural sky: airglow and
// starlight), 21.1 for class 4, 18.0 for class 8. Throws std::invalid_argument outside 1..9.
double bortle_zenith_mag_arcsec2(int bortle_class);

// Luminance (cd/m^2) of a surface brightness (V mag/arcsec^2): 1.08e5 x 10^(-0.4 m).
double sky_brightness_cd_m2(double mag_arcsec2);

}  // namespace cupola
