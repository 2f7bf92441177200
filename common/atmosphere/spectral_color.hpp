#pragma once
// Spectrum -> CIE 1931 XYZ -> linear sRGB for the atmosphere reference.
//
// Thin adapter over shaders/shared/star_color.glsl (compiled as C++ via shading/shared_shading.hpp):
// the colour-matching functions (the multi-lobe fit of Wyman, Sloan & Shirley 2013) and the
// IEC 61966-2-1 XYZ->sRGB matrix are that file's cie_xyz_bar() and xyz_to_linear_srgb(), so the
// atmosphere and the star colours share one set of numbers.
#include <glm/glm.hpp>

#include <vector>

namespace cupola::atmosphere {

inline constexpr double kLuminousEfficacy = 683.0;  // lm/W, photopic maximum (CIE)

// CIE 1931 2-degree colour-matching functions (x bar, y bar, z bar) at lambda_nm (multi-lobe fit).
glm::dvec3 cie1931_xyz_bar(double lambda_nm);

// IEC 61966-2-1 (D65) matrix; no clipping (negative components are kept).
glm::dvec3 xyz_to_linear_srgb(const glm::dvec3& xyz);

// Integrates spectra sampled at fixed wavelengths (trapezoid weights over the sample spacing).
// For a spectral radiance in W m^-2 sr^-1 nm^-1, xyz() and rgb() are photometric: Y (and the
// luminance 0.2126 R + 0.7152 G + 0.0722 B of rgb) is the luminance in cd m^-2.
class SpectralToColor {
public:
    explicit SpectralToColor(std::vector<double> wavelengths_nm);
    glm::dvec3 xyz(const std::vector<double>& spectrum) const;
    glm::dvec3 rgb(const std::vector<double>& spectrum) const { return xyz_to_linear_srgb(xyz(spectrum)); }
    double luminance(const std::vector<double>& spectrum) const { return xyz(spectrum).y; }

private:
    std::vector<double> lambdas_;
    std::vector<glm::dvec3> weights_;  // 683 * cmf * d lambda per sample
};

}  // namespace cupola::atmosphere
