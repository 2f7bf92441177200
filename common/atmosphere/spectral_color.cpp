#include "atmosphere/spectral_color.hpp"

#include <stdexcept>
#include <utility>

#include "shading/shared_shading.hpp"

namespace cupola::atmosphere {
glm::dvec3 cie1931_xyz_bar(double l) {
    // The colour-matching fit shared with the star colours (shaders/shared/star_color.glsl).
    return glm::dvec3(cupola::shading::cie_xyz_bar(static_cast<float>(l)));
}

glm::dvec3 xyz_to_linear_srgb(const glm::dvec3& v) {
    return glm::dvec3(cupola::shading::xyz_to_linear_srgb(glm::vec3(v)));
}

SpectralToColor::SpectralToColor(std::vector<double> wavelengths_nm) : lambdas_(std::move(wavelengths_nm)) {
    const std::size_t n = lambdas_.size();
    if (n < 2) throw std::invalid_argument("SpectralToColor needs at least two wavelengths");
    weights_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double lo = i == 0 ? lambdas_[0] : 0.5 * (lambdas_[i - 1] + lambdas_[i]);
        const double hi = i + 1 == n ? lambdas_[n - 1] : 0.5 * (lambdas_[i] + lambdas_[i + 1]);
        if (i > 0 && !(lambdas_[i] > lambdas_[i - 1]))
            throw std::invalid_argument("SpectralToColor: wavelengths must increase");
        weights_[i] = kLuminousEfficacy * (hi - lo) * cie1931_xyz_bar(lambdas_[i]);
    }
}

glm::dvec3 SpectralToColor::xyz(const std::vector<double>& spectrum) const {
    if (spectrum.size() != weights_.size()) throw std::invalid_argument("SpectralToColor: spectrum size");
    glm::dvec3 s(0.0);
    for (std::size_t i = 0; i < spectrum.size(); ++i) s += spectrum[i] * weights_[i];
    return s;
}

}  // namespace cupola::atmosphere
