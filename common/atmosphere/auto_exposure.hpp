#pragma once
// Cluster-wide automatic exposure. The master decides one exposure, display white and adaptation
// per frame from the state every channel shares (the snapshot and the scene), so all channels
// tone-map identically and no seam can come from exposure. It meters the luminance (scene units)
// seen along rays through every channel, weighted by the solid angle each stands for (shared
// once between overlapping channels), from the production atmosphere of every body that has one
// (sky, lit ground, limb), under the frame's eclipse shadows, with the Moon's light on the air
// where the slaves draw it (moonlit_sky.hpp), evaluated on the CPU by the same shared code the
// slaves run; exposure/sky_metering makes the log-average and highlight of it, and
// exposure/eye_adaptation the adaptation and the exposure. The metering is a pure function of
// the frame; the adaptation carries over from frame to frame in the master (EyeAdaptation), and
// the snapshot carries its state so that every frame can be reproduced from the snapshots.
#include <memory>
#include <vector>

#include "atmosphere/moonlit_sky.hpp"
#include "atmosphere/production_model.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "eclipse/shadow_casters.hpp"
#include "exposure/eye_adaptation.hpp"
#include "exposure/sky_metering.hpp"
#include "wire/snapshot.hpp"

namespace cupola {

class AutoExposure {
public:
    // atmospheres: the master's shared models (not owned; must outlive this), or nullptr to
    // build its own when auto exposure is enabled.
    AutoExposure(const ClusterConfig& cluster, const SceneConfig& scene, const SceneAtmospheres* atmospheres = nullptr);
    ~AutoExposure();

    // Rays per channel side of the master's metering: 8 x 8 costs 2.3 ms of CPU a frame on a
    // 4-channel dome at greatest eclipse, and its log-average stays within the error that
    // benchmarks/master_exposure measures against a 64 x 64 grid (BENCHMARKS.md).
    static constexpr int kMeterGrid = 8;
    // The metering of the view the cluster shows (grid x grid rays through every channel, solid-angle weighted).
    SkyMetering meter(const Snapshot& snap, int grid = kMeterGrid) const;
    // Its log-average luminance (scene units); 0 when nothing is lit.
    double metered_luminance(const Snapshot& snap) const { return meter(snap).log_average; }
    // The frame's exposure, white and adaptation. With `eye`, the adaptation steps on from the
    // previous frame by dt_s; without, the eye is adapted to this frame. Auto exposure off: the
    // fixed exposure, no display curve, no adaptation.
    ExposureDecision decide(const Snapshot& snap, EyeAdaptation* eye = nullptr, double dt_s = 0.0) const;
    // decide(snap).exposure: the exposure of an eye adapted to this frame.
    double exposure(const Snapshot& snap) const { return decide(snap).exposure; }

private:
    // The night sky's second light (atmosphere/moonlit_sky.hpp) as the master estimates it: the
    // brightest body with a measured phase curve, in units of the Sun's irradiance at 1 AU.
    SkySecondLight second_light(const Snapshot& snap, const BodyState& sun) const;
    static constexpr int kRefine = 4;  // an edge cell of the metering grid is cut into kRefine^2
    struct MeterCell {
        int channel;    // index into the cluster's channels
        double x, y;    // centre on the channel's image plane (tangents)
        double dx, dy;  // extent
    };
    struct MeterRay {
        glm::dvec3 dir_world;
        double weight_sr;
    };
    // The cluster's channel frusta, in channel order (built once per metering).
    std::vector<ChannelFrustum> channel_frusta() const;
    // The grid x grid cells of every channel's image plane, channel by channel, row by row.
    static std::vector<MeterCell> grid_cells(const std::vector<ChannelFrustum>& frusta, int grid);
    static std::vector<size_t> edge_cells(const std::vector<bool>& lit, int grid);
    static void split_cell(const MeterCell& c, std::vector<MeterCell>& out);
    // A ray through each cell's centre, with the solid angle the cell stands for, divided among
    // the channels that overlap there.
    std::vector<MeterRay> meter_rays(const Snapshot& snap, const std::vector<ChannelFrustum>& frusta,
                                     const std::vector<MeterCell>& cells) const;
    // The luminance along each ray, through every atmosphere (needs the scene's star).
    std::vector<double> luminances(const Snapshot& snap, const std::vector<MeterRay>& rays) const;
    // The Moon's sky along v (unit, world) in cd/m^2 per unit solar irradiance of the physical spectrum.
    static double moonlit_luminance(const atmosphere::ProductionAtmosphere& model, double d_m, const glm::dvec3& v,
                                    const glm::dvec3& c_hat, const MoonOnAir& moon);
    const ClusterConfig* cluster_;
    const SceneConfig* scene_;
    std::unique_ptr<SceneAtmospheres> own_atmospheres_;
    const SceneAtmospheres* atmospheres_ = nullptr;
    std::unique_ptr<ShadowCasting> casting_;  // eclipse shadows dim the sky the exposure sees
};

}  // namespace cupola
