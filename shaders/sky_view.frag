#version 450 core
// One texel of the sky-view table per fragment (shaders/shared/atmosphere_sky_view.glsl;
// slave/passes/sky_view_gpu.hpp): the viewport is the table, its three parts the three outputs.
uniform AtmosphereParams u_atm;
uniform sampler2D u_transmittance;
uniform sampler2D u_multiple_scattering;
uniform sampler2D u_irradiance;
uniform sampler2D u_weights;
uniform vec2 u_trans_size;
uniform vec2 u_ms_size;
uniform vec2 u_irr_size;
uniform float u_weight_count;
uniform float u_d_m;   // camera to planet centre
uniform float u_mu_s;  // Sun zenith cosine at the camera
uniform vec2 u_table_size;
uniform int u_samples;
// The second wavelength triplet (SKY_SIX_WAVELENGTHS, slave/passes/sky_view_gpu.cpp): its
// parameters and tables, the same sizes as the first's.
uniform AtmosphereParams u_atm2;
uniform sampler2D u_transmittance2;
uniform sampler2D u_multiple_scattering2;
uniform sampler2D u_irradiance2;

layout(location = 0) out vec4 out_phased;
layout(location = 1) out vec4 out_mie;
layout(location = 2) out vec4 out_third;

void main() {
    vec2 uv = gl_FragCoord.xy / u_table_size;
#if SKY_SIX_WAVELENGTHS
    AtmosphereSkyViewTexel t = atm_compute_sky_view6(
        u_atm, u_transmittance, u_trans_size, u_multiple_scattering, u_ms_size, u_irradiance, u_irr_size, u_atm2,
        u_transmittance2, u_multiple_scattering2, u_irradiance2, u_weights, u_weight_count, u_d_m, u_mu_s, uv,
        u_table_size, u_samples);
#else
    AtmosphereSkyViewTexel t =
        atm_compute_sky_view(u_atm, u_transmittance, u_trans_size, u_multiple_scattering, u_ms_size, u_irradiance,
                             u_irr_size, u_weights, u_weight_count, u_d_m, u_mu_s, uv, u_table_size, u_samples);
#endif
    out_phased = vec4(t.phased, 1.0);
    out_mie = vec4(t.mie, 1.0);
    out_third = vec4(t.third, 1.0);
}
