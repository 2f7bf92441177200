#pragma once
// The slave process for one channel: joins the cluster, renders every snapshot it receives into
// its frustum slice, hands it to its output stage (slave/output/projector_output), reports "ready N"
// to the master and shows the frame on its "present N" (the swap lock, docs/SWAP_LOCK.md).
#include <atomic>
#include <string>

#include "config/cluster_config.hpp"

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

private:
    struct Loop;  // one run's renderer, wire and protocol session (slave_node.cpp)

    ClusterConfig cluster_;
    ChannelConfig channel_;
    SlaveOptions options_;
    std::atomic<bool> stop_requested_{false};
};

}  // namespace cupola
