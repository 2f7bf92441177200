#pragma once
// The slave process for one channel: joins the cluster, renders every snapshot it receives into
// its frustum slice, writes the frame files and reports "frame N rendered" to the master.
#include <atomic>
#include <string>

#include "config/cluster_config.hpp"
#include "frame_presenter.hpp"

namespace cupola {

struct SlaveOptions {
    std::string out_dir;               // frame files go here
    int egl_device = -2;               // -2: from the config
    int idle_timeout_s = 30;           // exit when no snapshot arrives for this long (master gone)
    std::vector<std::string> formats;  // empty: from the config
    std::string stats_file;            // the counters as JSON, rewritten every second (--stats)
    std::string present_log;           // JSON lines, one per frame shown: ready and present times (--present-log)
};

class SlaveNode {
public:
    SlaveNode(ClusterConfig cluster, int channel_id, SlaveOptions options);
    int run();
    void stop() { stop_requested_ = true; }
    // The output's present (frame_presenter.hpp); the files output's by default.
    void set_presenter(FramePresenter presenter) { presenter_ = std::move(presenter); }

private:
    struct Loop;  // one run's renderer, wire and protocol session (slave_node.cpp)

    ClusterConfig cluster_;
    ChannelConfig channel_;
    SlaveOptions options_;
    FramePresenter presenter_ = files_presenter();
    std::atomic<bool> stop_requested_{false};
};

}  // namespace cupola
