#pragma once
// The master process: owns simulation time and the camera (from the show script), broadcasts one
// full snapshot per frame and runs the frame barrier over the channels' reports.
#include <atomic>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "atmosphere/auto_exposure.hpp"
#include "atmosphere/scene_atmospheres.hpp"
#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "glare/glare_sharing.hpp"
#include "glare/glare_sources.hpp"
#include "overlay_fader.hpp"
#include "show_script.hpp"

namespace cupola {

struct MasterOptions {
    std::optional<uint64_t> frames;  // stop after this many frames (none: run until stopped)
    std::string events_file;         // JSON lines: one object per frame and per channel event
    std::string stats_file;          // the counters as JSON, rewritten every second (--stats)
    // A master (re)started while slaves already rendered frames continues the show after the
    // last frame every one of them rendered, so a master restart leaves no channel a gap.
    bool resume = true;
    std::string control;  // control socket path, "-" for standard input ("" none)
};

// The snapshot for a frame as the show alone defines it: deterministic in the frame index, so
// any process (a test, a replay tool) can recompute it. With output.auto_exposure enabled, pass
// the AutoExposure built for the same cluster and scene; with glare, the GlareSources (the
// sources then carry their analytic visibility). The master broadcasts exactly this for frame 0;
// from frame 1 on it replaces the glare visibility by the cluster's measurement of the previous
// frame where it has one (GlareSharing), so later hashes also depend on the channels' reports.
Snapshot make_frame_snapshot(const ClusterConfig& cluster, const SceneConfig& scene, const ShowScript& show,
                             uint64_t frame, const AutoExposure* auto_exposure = nullptr,
                             const GlareSources* glare = nullptr);

// What the master adds to a frame's simulation state (show or live): the frame index, exposure
// (the show's or a control override, else the cluster's fixed or automatic one) with the display
// white and the eye's adaptation, the star limit, the glare phase (from the frame index, so it
// runs on in every mode) and the glare sources. `eye`: the adaptation carried from the previous
// frame (the master's); none: the eye adapted to this frame (make_frame_snapshot).
void finish_frame_snapshot(Snapshot& snap, const ShowSettings& settings, const ClusterConfig& cluster,
                           const SceneConfig& scene, uint64_t frame, double frame_interval_s,
                           const AutoExposure* auto_exposure, const GlareSources* glare, EyeAdaptation* eye = nullptr,
                           OverlayFader* overlays = nullptr);

class MasterNode {
public:
    MasterNode(ClusterConfig cluster, MasterOptions options);
    // Runs until the frame count is reached or stop() is called; tells the slaves to quit.
    // Returns the process exit code.
    int run();
    void stop() { stop_requested_ = true; }

private:
    struct Loop;  // one run's wire, protocol session and frame steps (master_node.cpp)

    ClusterConfig cluster_;
    SceneConfig scene_;
    ShowScript show_;
    MasterOptions options_;
    std::unique_ptr<SceneAtmospheres> atmospheres_;  // when auto exposure or glare needs them
    std::unique_ptr<AutoExposure> auto_exposure_;
    std::unique_ptr<GlareSources> glare_sources_;  // when the scene has glare
    EyeAdaptation eye_;                            // carried from frame to frame (auto exposure)
    OverlayFader overlays_;                        // the overlays' fades, frame to frame
    std::atomic<bool> stop_requested_{false};
};

}  // namespace cupola
