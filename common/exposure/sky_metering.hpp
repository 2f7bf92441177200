#pragma once
// What the eye meters of the sky the whole cluster shows: the solid-angle-weighted log-average of
// the luminance over the part of the view that is lit, and its highlight (a high quantile). The
// master takes luminance samples along rays through every channel (common/atmosphere/
// auto_exposure); this file holds the statistics, which know nothing of where samples come from.
//
// Why not the arithmetic mean over everything: a lit planet seen from orbit fills part of a black
// sky; the mean then falls with the planet's share of the view and the exposure burns the disc
// white, and a few very bright samples (the sky by the Sun) pull the mean far above what most of
// the view shows. The log-average (Reinhard, Stark, Shirley and Ferwerda 2002, §2, eq. 1) is the
// geometric mean, which a few bright samples do not dominate; and only what is lit takes part,
// since a black sky has no luminance to average. What is not black (within kSeenContrast of the
// brightest sample) gives the highlight, the luminance that kHighlightQuantile of its solid angle
// stays below; what is lit is within kLitContrast of that highlight. A faint haze over a black
// sky (the air's limb seen from orbit) is then not lit, and does not pull the average of a sunlit
// disc down. The highlight sets where the display curve reaches white
// (shaders/shared/tone_curve.glsl), so that at most 1 - kHighlightQuantile of the view clips.
#include <vector>

namespace cupola {

struct MeterSample {
    double luminance = 0.0;  // cd/m^2 (or the scene's relative unit)
    double weight = 0.0;     // the solid angle it stands for, sr (any common scale)
};

struct SkyMetering {
    static constexpr double kSeenContrast = 1e-6;       // not black: at least this times the brightest sample
    static constexpr double kHighlightQuantile = 0.99;  // of what is not black, below the highlight
    static constexpr double kLitContrast = 1e-2;        // lit: at least this times the highlight
    double log_average = 0.0;                           // over the lit samples; 0: nothing lit
    double highlight = 0.0;     // the luminance kHighlightQuantile of the seen solid angle stays below
    double lit_fraction = 0.0;  // the lit share of the metered solid angle
};

// Weights <= 0 and luminances that are not finite and positive count as unlit (black).
SkyMetering meter_sky(const std::vector<MeterSample>& samples);

// The solid angle of a cell dx x dy of a frustum's image plane at distance 1, centred at (x, y):
// dx dy / (1 + x^2 + y^2)^(3/2) (the plane's area seen from the eye).
double image_plane_cell_solid_angle(double x, double y, double dx, double dy);

}  // namespace cupola
