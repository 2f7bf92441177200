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
#include "show_script.hpp"

namespace cupola {

struct MasterOptions {
    std::optional<uint64_t> frames;  // stop after this many frames (none: run until stopped)
    std::string events_file;         // JSON lines: one object per frame and per channel event
};

// The snapshot the master broadcasts for a frame: deterministic in the frame index, so any
// process (a test, a replay tool) can recompute it and check a frame file's hash. With
// output.auto_exposure enabled, pass the AutoExposure built for the same cluster and scene.
Snapshot make_frame_snapshot(const ClusterConfig& cluster, const SceneConfig& scene, const ShowScript& show,
                             uint64_t frame, const AutoExposure* auto_exposure = nullptr);

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
    std::unique_ptr<AutoExposure> auto_exposure_;
    std::atomic<bool> stop_requested_{false};
};

}  // namespace cupola
