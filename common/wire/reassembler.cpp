#include "wire/reassembler.hpp"

#include <algorithm>
#include <cstring>

namespace cupola {

std::optional<Message> Reassembler::add(Packet&& p) {
    const auto& h = p.header;
    if (h.fragment_count == 1) return Message{h.type, h.sender, h.frame, std::move(p.payload), h.session};

    Key key{h.sender, h.session, static_cast<uint8_t>(h.type), h.frame};
    auto it = pending_.find(key);
    if (it == pending_.end()) {
        while (pending_.size() >= max_pending_) {
            auto oldest = std::min_element(pending_.begin(), pending_.end(), [](const auto& a, const auto& b) {
                return a.second.arrival < b.second.arrival;
            });
            pending_.erase(oldest);
            ++incomplete_dropped_;
        }
        Pending np;
        np.length = h.message_length;
        np.count = h.fragment_count;
        np.data.assign(h.message_length, 0);
        np.have.assign(h.fragment_count, false);
        np.arrival = ++arrivals_;
        it = pending_.emplace(key, std::move(np)).first;
    }
    Pending& m = it->second;
    if (m.length != h.message_length || m.count != h.fragment_count) {
        ++inconsistent_;
        return std::nullopt;
    }
    if (m.have[h.fragment_index]) {
        ++duplicates_;
        return std::nullopt;
    }
    if (!p.payload.empty()) std::memcpy(m.data.data() + h.fragment_offset, p.payload.data(), p.payload.size());
    m.have[h.fragment_index] = true;
    if (++m.received < m.count) return std::nullopt;
    Message done{h.type, h.sender, h.frame, std::move(m.data), h.session};
    pending_.erase(it);
    return done;
}

}  // namespace cupola
