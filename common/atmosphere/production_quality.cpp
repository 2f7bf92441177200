#include "atmosphere/production_quality.hpp"

#include <stdexcept>

namespace cupola::atmosphere {

std::string ProductionQuality::table_key() const {
    return std::string(analytic ? "analytic" : "lut") + ";T" + std::to_string(transmittance_width) + "x" +
           std::to_string(transmittance_height) + "s" + std::to_string(transmittance_steps) + ";M" +
           std::to_string(ms_size) + "d" + std::to_string(ms_directions) + "s" + std::to_string(ms_steps) +
           (ms_order_directions > 0 ? "n" + std::to_string(ms_order_directions) : "") + "o" +
           std::to_string(ms_orders) + (ms_rayleigh_anisotropy ? "a" : "") + ";E" + std::to_string(irradiance_width) +
           "x" + std::to_string(irradiance_height) + "d" + std::to_string(irradiance_directions) + "s" +
           std::to_string(irradiance_samples) + (multiple_scattering ? ";ms" : ";single") +
           (sky_view && sky_view_wavelengths == 6 ? ";w6" : "");
}

namespace {
ProductionQuality level(const std::string& name, int tw, int th, int ts, int ms, int md, int mst, int iw, int ih,
                        int id, int is, int view) {
    ProductionQuality q;
    q.name = name;
    q.transmittance_width = tw;
    q.transmittance_height = th;
    q.transmittance_steps = ts;
    q.ms_size = ms;
    q.ms_directions = md;
    q.ms_steps = mst;
    q.irradiance_width = iw;
    q.irradiance_height = ih;
    q.irradiance_directions = id;
    q.irradiance_samples = is;
    q.view_samples = view;
    return q;
}
}  // namespace

std::vector<std::string> production_quality_names() {
    return {"analytic", "single", "hillaire", "low", "medium", "sky-view-rgb", "sky-view"};
}

ProductionQuality production_quality(const std::string& name) {
    if (name == "analytic") {
        ProductionQuality q = level(name, 64, 16, 40, 2, 4, 4, 2, 2, 4, 4, 1);
        q.analytic = true;
        q.multiple_scattering = false;
        return q;
    }
    if (name == "single") {
        ProductionQuality q = level(name, 256, 64, 40, 2, 4, 4, 64, 16, 64, 16, 16);
        q.multiple_scattering = false;
        return q;
    }
    if (name == "hillaire") {  // medium's tables with Hillaire's geometric multiple-scattering tail
        ProductionQuality q = level(name, 256, 64, 40, 32, 64, 20, 64, 16, 64, 16, 16);
        q.ms_orders = 0;
        return q;
    }
    if (name == "low") {
        ProductionQuality q = level(name, 64, 16, 20, 16, 32, 10, 32, 8, 32, 8, 8);
        q.ms_orders = 4;
        return q;
    }
    if (name == "medium") {
        ProductionQuality q = level(name, 256, 64, 40, 32, 64, 20, 64, 16, 64, 16, 16);
        q.ms_rayleigh_anisotropy = true;
        return q;
    }
    if (name == "sky-view" || name == "sky-view-rgb") {  // medium's tables, looked up through a sky-view table
        // The second order from 128 directions (64 miss the thin lit ring the shadowed air sees in
        // twilight), the smoother higher orders from 32.
        ProductionQuality q = level(name, 256, 64, 40, 64, 128, 12, 128, 32, 64, 16, 16);
        q.ms_order_directions = 32;
        q.ms_rayleigh_anisotropy = true;
        q.sky_view = true;
        q.sky_view_wavelengths = name == "sky-view" ? 6 : 3;
        return q;
    }
    std::string list;
    for (const auto& n : production_quality_names()) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown atmosphere model '" + name + "' (expected one of: " + list + ")");
}

}  // namespace cupola::atmosphere
