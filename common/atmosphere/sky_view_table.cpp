#include "atmosphere/sky_view_table.hpp"

#include <algorithm>
#include <cmath>

#include "atmosphere/production_model.hpp"

namespace cupola::atmosphere {
using namespace cupola::shading;

float sky_view_table_sun_mu(double mu_s) {
    const double step = glm::radians(kSkyViewSunStep_deg);
    const double zenith = std::acos(std::clamp(mu_s, -1.0, 1.0));
    return static_cast<float>(std::cos(std::round(zenith / step) * step));
}

SkyViewTable build_sky_view_table(const ProductionAtmosphere& m, float d_m, float mu_s) {
    const ProductionQuality& q = m.quality();
    const ProductionTables& tables = m.tables();
    SkyViewTable out;
    out.d_m = d_m;
    out.mu_s = mu_s;
    for (auto& p : out.parts) {
        p.width = q.sky_view_width;
        p.height = q.sky_view_height;
        p.texels.assign(static_cast<size_t>(p.width) * p.height, glm::vec4(0.0f));
    }
    const vec2 size = out.size();
    const sampler2D trans{&tables.transmittance}, ms{&tables.multiple_scattering}, irr{&tables.irradiance};
    const sampler2D weights{&m.color_weights()};
    const vec2 ts(tables.transmittance.width, tables.transmittance.height);
    const vec2 mss(tables.multiple_scattering.width, tables.multiple_scattering.height);
    const vec2 es(tables.irradiance.width, tables.irradiance.height);
    const float n = static_cast<float>(m.color_weights().width);
    const ProductionTables& t2 = m.tables2();
    const sampler2D trans2{&t2.transmittance}, ms2{&t2.multiple_scattering}, irr2{&t2.irradiance};
    for (int y = 0; y < q.sky_view_height; ++y)
        for (int x = 0; x < q.sky_view_width; ++x) {
            const vec2 uv((x + 0.5f) / size.x, (y + 0.5f) / size.y);
            const AtmosphereSkyViewTexel t =
                m.six_wavelengths()
                    ? atm_compute_sky_view6(m.shader_params(), trans, ts, ms, mss, irr, es, m.shader_params2(), trans2,
                                            ms2, irr2, weights, n, d_m, mu_s, uv, size, q.sky_view_samples)
                    : atm_compute_sky_view(m.shader_params(), trans, ts, ms, mss, irr, es, weights, n, d_m, mu_s, uv,
                                           size, q.sky_view_samples);
            const size_t i = static_cast<size_t>(y) * q.sky_view_width + x;
            out.parts[0].texels[i] = glm::vec4(t.phased, 1.0f);
            out.parts[1].texels[i] = glm::vec4(t.mie, 1.0f);
            out.parts[2].texels[i] = glm::vec4(t.third, 1.0f);
        }
    return out;
}

}  // namespace cupola::atmosphere
