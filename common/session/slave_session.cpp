#include "session/slave_session.hpp"

#include <spdlog/spdlog.h>

#include "wire/byte_io.hpp"

namespace cupola {

SlaveSession::SlaveSession(SlaveSessionConfig config, Clock::time_point start)
    : config_(std::move(config)), last_snapshot_(start) {
    hello_.channel = static_cast<uint16_t>(config_.channel);
    hello_.process_id = config_.process_id;
}

void SlaveSession::receive(ReceivedMessage rm) { inbox_.push_back(std::move(rm)); }

SlaveActions SlaveSession::tick(Clock::time_point now) {
    SlaveActions out;
    if (exited_) return out;
    if (linger_until_) {
        if (now >= *linger_until_) {
            exited_ = true;
            out.exit_code = 0;
        }
        return out;
    }
    // Say hello until we are welcomed and snapshots flow, and whenever snapshots stop (we may have
    // been dropped). To session 0 — "whoever is master, welcome me" — while a master we do not know
    // is sending, and after a second without snapshots: a restarted master rejects hellos addressed
    // to its predecessor and sends nothing until channels join.
    const bool joining = master_session_ == 0 || need_welcome_ || !rendered_in_session_;
    const bool silent = now - last_snapshot_ > kSilentAfter;
    const bool quiet = now - last_snapshot_ > kQuietHelloInterval;
    auto hello_older_than = [&](std::chrono::milliseconds d) { return !last_hello_ || now - *last_hello_ > d; };
    if ((joining && hello_older_than(kJoinHelloInterval)) || (quiet && hello_older_than(kQuietHelloInterval)))
        send_hello(need_welcome_ || silent ? 0 : master_session_, now, out);
    if (now - last_snapshot_ > config_.idle_timeout) {
        spdlog::error("{}: no snapshot for {} s; is the master running? exiting", config_.log_name,
                      config_.idle_timeout.count());
        exited_ = true;
        out.exit_code = 3;
    }
    return out;
}

SlaveSession::Clock::time_point SlaveSession::next_wake(Clock::time_point now) const {
    return linger_until_ ? *linger_until_ : now + kJoinHelloInterval;
}

SlaveActions SlaveSession::step(Clock::time_point now) {
    SlaveActions out;
    if (inbox_.empty() || exited_) return out;
    ReceivedMessage rm = std::move(inbox_.front());
    inbox_.pop_front();
    if (rm.message.sender != kMasterSender) return out;
    if (linger_until_) {
        linger(rm, out);
        return out;
    }
    handle(std::move(rm), now, out);
    return out;
}

void SlaveSession::handle(ReceivedMessage rm, Clock::time_point now, SlaveActions& out) {
    if (rm.opened) {
        opened(rm, now, out);
    } else if (!rm.verified) {
        if (!need_welcome_)
            spdlog::info("{}: a master session {:016x} we do not know is sending: asking it for a welcome",
                         config_.log_name, rm.message.session);
        need_welcome_ = true;
        return;
    }
    if (!rm.verified) return;  // opened by a fragment of a message not yet whole
    const Message& m = rm.message;
    if (m.type == PacketType::Welcome) {
        if (!rm.opened && (!last_hello_ || now - *last_hello_ > kJoinHelloInterval))
            send_hello(master_session_, now, out);
    } else if (m.type == PacketType::Present) {
        present(m, out);
    } else if (m.type == PacketType::Quit) {
        // Confirm, and keep confirming for a moment in case our confirmation is lost; the quit
        // comes after the last frame's present, so it implies it.
        release(PresentCause::Implied, out);
        quit_frame_ = m.frame;
        send_quit_ack(out);
        linger_until_ = now + kQuitLinger;
    } else if (m.type == PacketType::Snapshot) {
        catch_up(rm);
        snapshot(rm, now, out);
    }
}

void SlaveSession::opened(const ReceivedMessage& rm, Clock::time_point now, SlaveActions& out) {
    master_session_ = rm.message.session;
    ++counters_.master_sessions;
    need_welcome_ = false;
    fresh_session_ = true;
    rendered_in_session_ = false;
    spdlog::info("{}: welcomed by master session {:016x}", config_.log_name, master_session_);
    send_hello(master_session_, now, out);  // completes the handshake: the master now knows us
}

void SlaveSession::linger(const ReceivedMessage& rm, SlaveActions& out) {
    if (rm.verified && rm.message.type == PacketType::Quit) send_quit_ack(out);
}

// Catching up after a stall: when newer snapshots of the same master session are already queued,
// only the newest is rendered; the rest of the queue keeps its order.
void SlaveSession::catch_up(ReceivedMessage& current) {
    std::deque<ReceivedMessage> rest;
    for (ReceivedMessage& more : inbox_) {
        const Message& n = more.message;
        if (more.verified && !more.opened && n.sender == kMasterSender && n.type == PacketType::Snapshot &&
            n.session == current.message.session && n.frame > current.message.frame) {
            ++counters_.skipped_snapshots;
            current = std::move(more);
        } else {
            rest.push_back(std::move(more));
        }
    }
    inbox_ = std::move(rest);
}

void SlaveSession::snapshot(const ReceivedMessage& rm, Clock::time_point now, SlaveActions& out) {
    const Message& sm = rm.message;
    last_snapshot_ = now;
    const std::string hash = snapshot_hash(sm.payload);
    if (repeat_or_ignore(sm, hash, out)) return;
    std::optional<Snapshot> snap = decode(sm);
    if (!snap) return;
    if (last_frame_ && snap->frame > *last_frame_ + 1) {
        counters_.missed_frames += snap->frame - *last_frame_ - 1;
        spdlog::warn("{}: frames {}..{} never reached this channel ({} missed so far)", config_.log_name,
                     *last_frame_ + 1, snap->frame - 1, counters_.missed_frames);
    }
    // The master sends the next snapshot only after the held frame's present: it implies it, and no
    // frame is rendered before the one held is shown.
    release(PresentCause::Implied, out);
    job_ = Job{snap->frame, hash};
    out.render = RenderJob{std::move(*snap), hash};
}

// True when the snapshot needs no render: the frame we rendered last again (the master resends
// while it waits: our report was lost, or it restarted; the report is repeated), or an older one.
bool SlaveSession::repeat_or_ignore(const Message& sm, const std::string& hash, SlaveActions& out) {
    if (last_frame_ && sm.frame == *last_frame_ && last_report_) {
        if (hash == last_report_->snapshot_hash) {
            ++counters_.resent_snapshots;
            rendered_in_session_ = true;
            fresh_session_ = false;
            out.sends.push_back({PacketType::FrameDone, sm.frame, encode_frame_report(*last_report_), master_session_});
            return true;
        }
        if (!fresh_session_) {
            ++counters_.late_snapshots;  // same frame, other content, same master: cannot be; ignore
            return true;
        }
        ++counters_.rerendered;
    } else if (last_frame_ && sm.frame < *last_frame_ && !fresh_session_) {
        ++counters_.late_snapshots;  // reordered or a stale resend
        return true;
    }
    return false;
}

std::optional<Snapshot> SlaveSession::decode(const Message& sm) {
    try {
        Snapshot snap = decode_snapshot(sm.payload.data(), sm.payload.size());
        if (snap.frame != sm.frame) throw WireError("snapshot frame differs from its packet header");
        for (const auto& b : snap.bodies)
            if (b.id >= config_.scene_body_count)
                throw WireError("body id " + std::to_string(b.id) + " is not in the scene " + config_.scene_file +
                                " (" + std::to_string(config_.scene_body_count) +
                                " bodies): do the master and this slave use the same scene file?");
        return snap;
    } catch (const WireError& e) {
        ++counters_.malformed_snapshots;
        spdlog::warn("{}: malformed snapshot for frame {} dropped: {} ({} so far)", config_.log_name, sm.frame,
                     e.what(), counters_.malformed_snapshots);
        return std::nullopt;
    }
}

SlaveActions SlaveSession::rendered(FrameReport rep, uint64_t wire_rejected) {
    SlaveActions out;
    if (!job_) return out;
    rep.channel = static_cast<uint16_t>(config_.channel);
    rep.frame = job_->frame;
    rep.snapshot_hash = job_->hash;
    rep.packets_rejected = wire_rejected + counters_.malformed_snapshots;
    rep.snapshots_missed = counters_.missed_frames;
    PresentTiming timing = last_present_.value_or(PresentTiming{});
    timing.ready_ns = rep.presentation ? rep.presentation->ready_ns : 0;
    rep.presentation = timing;
    job_.reset();
    out.sends.push_back({PacketType::FrameDone, rep.frame, encode_frame_report(rep), master_session_});
    held_ = PresentJob{rep.frame, timing.ready_ns, PresentCause::Present};
    if (!config_.swap_lock) release(PresentCause::Unlocked, out);
    last_frame_ = rep.frame;
    last_report_ = std::move(rep);
    fresh_session_ = false;
    rendered_in_session_ = true;
    ++counters_.frames_rendered;
    return out;
}

// The master's present: shows the held frame when it names it or a later one (a later one: the
// master went on, so ours is due too); anything else is late or repeated.
void SlaveSession::present(const Message& m, SlaveActions& out) {
    uint64_t frame = 0;
    try {
        frame = decode_present(m.payload).frame;
        if (frame != m.frame) throw WireError("present frame differs from its packet header");
    } catch (const WireError& e) {
        ++counters_.stale_presents;
        spdlog::warn("{}: malformed present dropped: {}", config_.log_name, e.what());
        return;
    }
    if (!held_ || frame < held_->frame) {
        ++counters_.stale_presents;
        return;
    }
    release(frame == held_->frame ? PresentCause::Present : PresentCause::Implied, out);
}

void SlaveSession::release(PresentCause cause, SlaveActions& out) {
    if (!held_) return;
    out.present = *held_;
    out.present->cause = cause;
    held_.reset();
    ++counters_.frames_presented;
    if (cause == PresentCause::Implied) ++counters_.presents_implied;
}

void SlaveSession::presented(uint64_t frame, uint64_t present_ns) {
    last_present_ = PresentTiming{0, true, frame, present_ns};
}

std::optional<uint64_t> SlaveSession::held_frame() const {
    if (!held_) return std::nullopt;
    return held_->frame;
}

const char* present_cause_name(PresentCause c) {
    switch (c) {
        case PresentCause::Present:
            return "present";
        case PresentCause::Implied:
            return "implied";
        case PresentCause::Unlocked:
            return "unlocked";
    }
    return "?";
}

void SlaveSession::send_hello(uint64_t to, Clock::time_point now, SlaveActions& out) {
    hello_.has_frame = last_frame_.has_value();
    hello_.last_frame = last_frame_.value_or(0);
    out.sends.push_back({PacketType::Hello, hello_.last_frame, encode_hello(hello_), to});
    ++counters_.hellos_sent;
    last_hello_ = now;
}

void SlaveSession::send_quit_ack(SlaveActions& out) {
    out.sends.push_back({PacketType::QuitAck, quit_frame_, encode_hello(hello_), master_session_});
}

}  // namespace cupola
