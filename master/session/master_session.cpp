#include "session/master_session.hpp"

#include <spdlog/spdlog.h>

#include "wire/byte_io.hpp"

#include <string>

namespace cupola {

MasterSession::MasterSession(const std::vector<int>& channel_ids, uint64_t session, MasterTimings timings)
    : ids_(channel_ids),
      session_(session),
      timings_(timings),
      barrier_(channel_ids, timings.channel_timeout, timings.first_frame_timeout) {}

MasterActions MasterSession::on_message(const ReceivedMessage& rm, Clock::time_point now) {
    MasterActions out;
    const Message& m = rm.message;
    if (!barrier_.known(m.sender)) {
        if (++counters_.unknown_channel <= 3 || counters_.unknown_channel % 100 == 0)
            spdlog::warn("master: message from unknown channel {} at {} ignored ({} so far)", m.sender,
                         to_string(rm.from), counters_.unknown_channel);
        return out;
    }
    try {
        if (m.type == PacketType::Hello)
            hello(rm, now, out);
        else if (rm.verified)  // only hellos are answered before the handshake
            verified(rm, now, out);
    } catch (const WireError& e) {
        ++counters_.malformed_messages;
        spdlog::warn("master: malformed {} from channel {}: {}", packet_type_name(m.type), m.sender, e.what());
    }
    return out;
}

void MasterSession::hello(const ReceivedMessage& rm, Clock::time_point now, MasterActions& out) {
    const Message& m = rm.message;
    const HelloMessage h = decode_hello(m.payload);
    if (h.channel != m.sender) throw WireError("hello names another channel than its sender");
    if (rm.to_session != session_) {
        welcome(m, h, now, out);
        return;
    }
    hellos_[m.sender] = h;
    const bool was_live = barrier_.state(m.sender) == ChannelState::Live;
    if (rm.opened)
        barrier_.on_restart(m.sender, now);
    else if (!barrier_.on_alive(m.sender, now))
        return;
    ++counters_.channel_joins;
    if (rm.opened && was_live) ++counters_.channel_restarts;
    spdlog::info("master: channel {} joined (pid {}, {}){}", m.sender, h.process_id,
                 h.has_frame ? "last frame " + std::to_string(h.last_frame) : "no frame yet",
                 rm.opened && was_live ? ", a new process replacing a live one" : "");
    out.events.push_back({{"event", "channel_joined"},
                          {"channel", m.sender},
                          {"frame", frame_},
                          {"pid", h.process_id},
                          {"new_process", rm.opened}});
    out.joined.push_back(m.sender);
    // A (re)joined channel renders the current frame.
    if (phase_ == MasterPhase::Frame || phase_ == MasterPhase::Between) resend(now, out);
}

// A process that has not seen this master's session yet: prove it is live now.
void MasterSession::welcome(const Message& m, const HelloMessage& h, Clock::time_point now, MasterActions& out) {
    auto last = last_welcome_.find(m.sender);
    if (last != last_welcome_.end() && now - last->second < kWelcomeInterval) return;
    out.sends.push_back({PacketType::Welcome, frame_, encode_welcome({h.channel, frame_}), m.session});
    last_welcome_[m.sender] = now;
    ++counters_.welcomes_sent;
}

void MasterSession::verified(const ReceivedMessage& rm, Clock::time_point now, MasterActions& out) {
    const Message& m = rm.message;
    switch (m.type) {
        case PacketType::FrameDone:
            report(m, now, out);
            break;
        case PacketType::QuitAck:
            if (quit_acked_.insert(m.sender).second) ++counters_.quit_acks;
            break;
        default:
            spdlog::warn("master: unexpected {} message from channel {}", packet_type_name(m.type), m.sender);
            break;
    }
}

void MasterSession::report(const Message& m, Clock::time_point now, MasterActions& out) {
    FrameReport rep = decode_frame_report(m.payload);
    if (rep.channel != m.sender) throw WireError("report names another channel than its sender");
    const bool was_live = barrier_.state(m.sender) == ChannelState::Live;
    if (!barrier_.on_report(m.sender, rep.frame, now)) {
        ++counters_.late_reports;
        return;
    }
    if (!was_live) {
        ++counters_.channel_joins;
        out.events.push_back({{"event", "channel_joined"}, {"channel", m.sender}, {"frame", frame_}});
        out.joined.push_back(m.sender);
    }
    if (phase_ != MasterPhase::Frame) return;  // only the frame's own wait keeps reports
    maybe_present(now, out);
    if (sent_ns_ && rep.snapshot_received_ns >= sent_ns_)
        rep.snapshot_received_ns -= sent_ns_;
    else
        rep.snapshot_received_ns = 0;
    reports_[m.sender] = std::move(rep);
}

MasterActions MasterSession::start_frame(uint64_t frame, std::vector<uint8_t> payload, Clock::time_point now,
                                         uint64_t sent_ns) {
    MasterActions out;
    phase_ = MasterPhase::Frame;
    frame_ = frame;
    payload_ = std::move(payload);
    sent_ns_ = sent_ns;
    reports_.clear();
    presented_ = false;
    barrier_.start_frame(frame, now);
    out.sends.push_back({PacketType::Snapshot, frame_, payload_, 0});
    ++counters_.snapshots_sent;
    last_send_ = now;
    maybe_present(now, out);  // no live channel: nothing to wait for
    return out;
}

std::map<int, FrameReport> MasterSession::end_frame() {
    phase_ = MasterPhase::Between;
    sent_ns_ = 0;
    return std::move(reports_);
}

// A lost datagram costs a resend, not the session.
void MasterSession::resend(Clock::time_point now, MasterActions& out) {
    out.sends.push_back({PacketType::Snapshot, frame_, payload_, 0});
    ++counters_.snapshot_resends;
    last_send_ = now;
}

MasterActions MasterSession::tick(Clock::time_point now) {
    MasterActions out;
    if (phase_ == MasterPhase::Quitting) {
        if (now >= round_end_) quit_round(now, out);
        return out;
    }
    if (presented_ && now >= last_present_ + timings_.resend_interval) {
        ++counters_.present_resends;
        send_present(now, out);
    }
    if (phase_ != MasterPhase::Frame) return out;
    for (int id : barrier_.expire(now)) {
        ++counters_.channel_drops;
        spdlog::warn("master: channel {} silent for {} ms at frame {}: dropped, the others go on", id,
                     timings_.channel_timeout.count(), frame_);
        out.events.push_back({{"event", "channel_dropped"}, {"channel", id}, {"frame", frame_}});
        out.dropped.push_back(id);
    }
    maybe_present(now, out);
    if (!barrier_.complete() && now >= last_send_ + timings_.resend_interval) resend(now, out);
    return out;
}

MasterSession::Clock::time_point MasterSession::next_wake() const {
    if (phase_ == MasterPhase::Quitting) return round_end_;
    const auto present = presented_ ? last_present_ + timings_.resend_interval : Clock::time_point::max();
    if (phase_ != MasterPhase::Frame) return present;
    return std::min({last_send_ + timings_.resend_interval, barrier_.next_deadline(), present});
}

// Swap lock: the frame's present, once, as soon as no live channel is still expected to report.
void MasterSession::maybe_present(Clock::time_point now, MasterActions& out) {
    if (!timings_.swap_lock || presented_ || phase_ != MasterPhase::Frame || !barrier_.complete()) return;
    presented_ = true;
    ++counters_.presents_sent;
    send_present(now, out);
}

void MasterSession::send_present(Clock::time_point now, MasterActions& out) {
    out.sends.push_back({PacketType::Present, frame_, encode_present({frame_}), 0});
    last_present_ = now;
}

// Tell the slaves to quit, again every round until every live channel confirmed (for a limited
// time): a lost datagram must not leave one running.
MasterActions MasterSession::start_quit(uint64_t frame, Clock::time_point now) {
    MasterActions out;
    phase_ = MasterPhase::Quitting;
    presented_ = false;  // the quit implies the last present
    frame_ = frame;
    quit_until_ = now + kQuitLimit;
    quit_round(now, out);
    return out;
}

void MasterSession::quit_round(Clock::time_point now, MasterActions& out) {
    if (unconfirmed_quits().empty() || now >= quit_until_) {
        phase_ = MasterPhase::Done;
        return;
    }
    out.sends.push_back({PacketType::Quit, frame_ + 1, {}, 0});
    round_end_ = now + kQuitRound;
}

std::vector<int> MasterSession::unconfirmed_quits() const {
    std::vector<int> out;
    for (int id : ids_)
        if (barrier_.state(id) == ChannelState::Live && !quit_acked_.count(id)) out.push_back(id);
    return out;
}

std::optional<uint64_t> MasterSession::resume_after() const {
    std::optional<uint64_t> after;
    for (const auto& [id, h] : hellos_) {
        if (barrier_.state(id) != ChannelState::Live) continue;
        if (!h.has_frame) return std::nullopt;
        after = std::min(after.value_or(h.last_frame), h.last_frame);
    }
    return after;
}

}  // namespace cupola
