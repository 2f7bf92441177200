#pragma once
// The master process: owns simulation time and the camera (from the show script), broadcasts one
// full snapshot per frame and runs the frame barrier over the channels' reports.
#include <atomic>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "config/cluster_config.hpp"
#include "config/scene_config.hpp"
#include "auto_exposure.hpp"
#include "glare_sharing.hpp"
#include "glare_sources.hpp"
#include "scene_atmospheres.hpp"
#include "show_script.hpp"

namespace cupola {

struct MasterOptions {
    std::optional<uint64_t> frames;  // stop after this many frames (none: run until stopped)
    std::string events_file;         // JSON lines: one object per frame and per channel event
    std::string stats_file;          // the counters as JSON, rewritten every second (--stats)
    // A master (re)started while slaves already rendered frames continues the show after the
    // last frame every one of them rendered, so a master restart leaves no channel a gap.
    bool resume = true;
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

class MasterNode {
public:
    MasterNode(ClusterConfig cluster, MasterOptions options);
    // Runs until the frame count is reached or stop() is called; tells the slaves to quit.
    // Returns the process exit code.
    int run();
    void stop() { stop_requested_ = true; }

private:
    ClusterConfig cluster_;
    SceneConfig scene_;
    ShowScript show_;
    MasterOptions options_;
    std::unique_ptr<SceneAtmospheres> atmospheres_;  // when auto exposure or glare needs them
    std::unique_ptr<AutoExposure> auto_exposure_;
    std::unique_ptr<GlareSources> glare_sources_;    // when the scene has glare
    std::atomic<bool> stop_requested_{false};
};

}  // namespace cupola
