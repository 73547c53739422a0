#pragma once
/// The Sparkplug session of a pair (docs/redundancy.md): the two units are one edge node, and
/// only the leader holds its session. A unit that takes the lead opens a new one, whose bdSeq a
/// Sparkplug host must see differ from the old leader's: the old session's NDEATH, should the
/// broker deliver it late (a leader cut off from the broker, whose will fires once its
/// connection times out), then names a session that is already over, and the host leaves the
/// new one alive. Pure.

#include <cstdint>
#include <optional>

namespace eip2mqtt::core::redundancy {

/// The bdSeq of the session a new leader opens: one more (mod 256, as the node counts) than
/// `heard`, the last bdSeq this unit read in a leader record of its pair; without one, `own_next`,
/// the one its own node would take next.
std::uint8_t next_session_bd_seq(std::optional<std::uint8_t> heard, std::uint8_t own_next);

}  // namespace eip2mqtt::core::redundancy
