// Snapshot path cost on real loopback UDP: encode + HMAC + fragment + send, then receive +
// verify + reassemble + decode on a second socket, for small and large snapshots.
//   build/bin/bench_wire --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "net/wire_endpoint.hpp"
#include "support/wire_handshake.hpp"
#include "wire/reports.hpp"
#include "wire/snapshot.hpp"

using namespace cupola;

namespace {

Snapshot snapshot_with(int bodies) {
    Snapshot s;
    s.frame = 1;
    s.sim_time_s = 7.6e8;
    s.camera_position_m = {1.5e11, -2.0e7, 3.0e6};
    for (int i = 0; i < bodies; ++i)
        s.bodies.push_back({static_cast<uint16_t>(i), {1e11 + i, 2e9, -3e8}, {1, 0, 0, 0}});
    return s;
}

void BM_SnapshotLoopbackRoundTrip(benchmark::State& state) {
    ClusterConfig cfg;
    cfg.cluster_id = 9;
    cfg.network.transport = Transport::Unicast;
    cfg.network.report_port = 47991;
    cfg.network.max_datagram_bytes = 1400;
    ChannelConfig ch;
    ch.id = 0;
    ch.unicast_address = "127.0.0.1:47990";
    cfg.channels.push_back(ch);
    AuthKey key{};
    key.fill(7);
    WireEndpoint master = open_master_endpoint(cfg, key, new_session_nonce());
    std::vector<WireEndpoint> slaves;
    slaves.push_back(open_slave_endpoint(cfg, ch, key, new_session_nonce()));
    WireEndpoint& slave = slaves.front();
    const auto dest = snapshot_destinations(cfg);
    // The slave acts only on a master session it joined: the sessions' own handshake.
    if (!test::handshake(master, slaves, cfg)) {
        state.SkipWithError("no handshake on loopback");
        return;
    }
    Snapshot snap = snapshot_with(static_cast<int>(state.range(0)));
    std::vector<double> us;
    size_t datagrams = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        ++snap.frame;
        const auto before = master.counters().datagrams_sent;
        master.send(PacketType::Snapshot, snap.frame, encode_snapshot(snap), dest);
        datagrams = master.counters().datagrams_sent - before;
        auto m = slave.receive(1000);
        if (!m) {
            state.SkipWithError("snapshot lost on loopback");
            break;
        }
        Snapshot got = decode_snapshot(m->message.payload.data(), m->message.payload.size());
        benchmark::DoNotOptimize(got);
        us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(us.begin(), us.end());
    if (!us.empty()) {
        state.counters["median_us"] = us[us.size() / 2];
        state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
    }
    state.counters["datagrams"] = static_cast<double>(datagrams);
    state.counters["bytes"] = static_cast<double>(encode_snapshot(snap).size());
}

}  // namespace

BENCHMARK(BM_SnapshotLoopbackRoundTrip)->Arg(3)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
