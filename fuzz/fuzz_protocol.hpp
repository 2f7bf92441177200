#pragma once
// Mode::Protocol of cupola-fuzz-wire (fuzz_wire_format.hpp): a master and its slaves, each the
// nodes' own session code (MasterSession, SlaveSession) behind a SessionGuard with the endpoints'
// open policies (session/handshake.hpp), exchanging datagrams that the fuzz input delays, drops,
// replays and forges, while time advances by fuzz-chosen steps and processes restart.
#include "fuzz_wire_format.hpp"

namespace cupola::fuzz {

// Runs one protocol script; a broken invariant aborts (reported by libFuzzer).
void run_protocol(Reader& r);

}  // namespace cupola::fuzz
