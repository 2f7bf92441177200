#pragma once
// The join handshake's rule on the guard's side (wire/session_guard.hpp): which authentic datagram
// from a session not established yet opens it, per role. The endpoints (net/wire_endpoint.cpp) and
// the fuzz target (fuzz/fuzz_wire_decoder.cpp) use these, so the rule is written once; what each
// side answers is in MasterSession (master/session/) and SlaveSession (session/slave_session.hpp).
#include <cstdint>

#include "wire/session_guard.hpp"

namespace cupola {

// The master opens a slave's session on a Hello addressed to its own session `self`; other Hellos
// go up unverified (to be answered with a Welcome), anything else from an unknown session is
// rejected, and its own multicast looped back is ignored.
SessionGuard::OpenPolicy master_open_policy(uint64_t self);

// A slave opens the master's session on a Welcome addressed to its own session `self`; the
// master's other packets go up unverified (a sign that the master restarted), other nodes'
// traffic is ignored.
SessionGuard::OpenPolicy slave_open_policy(uint64_t self);

}  // namespace cupola
