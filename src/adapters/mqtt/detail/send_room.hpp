#pragma once
/// When the sender may hand Paho one more publication: the two windows it keeps, as pure rules.
///
/// - Publications in flight at any QoS, up to max_in_flight (256). Once the sender filled it,
///   it waits until an eighth of it completed, so that it wakes once per burst rather than
///   once per completion, yet keeps the window nearly full: at QoS 1 a busy broker's PUBACKs
///   take milliseconds, and throughput is what is in flight over that time (refilling at a
///   quarter cost a third of it).
/// - Of those, the ones awaiting an acknowledgement (QoS >= 1), up to the broker's Receive
///   Maximum (Mosquitto's default: 20). Paho C holds any beyond it until its next one-second
///   cycle, so the client's own QoS >= 1 publications (`online`, `offline`), which Paho has
///   outside the window, take their slots while the broker has not acknowledged them. This
///   window refills one slot at a time, as bare Paho does: it is small and round-trip bound,
///   and with two of 20 slots empty on average the gateway's QoS 1 rate on Debian's default
///   broker was measurably lower.
/// - Except on a saturated connection: a backlog that outlasted kSaturatedWindows windows of
///   publications is one the connection cannot carry, not a burst. There, each slot refilled
///   alone cost a wake-up of the sender and of Paho's send thread, and a TCP segment, per
///   publication: the acknowledged window refills two slots at a time (the sender's Nagle on,
///   see NagleSwitch), which packs publications and the broker's PUBACKs several to a segment.
///   Not more than two: against Mosquitto's own Nagle, waiting for four free slots left the
///   sender waiting on PUBACKs the broker held for our delayed ACK (3,000 publications/s
///   instead of 12,000).
///
/// Module-private (src/adapters/mqtt/detail).

#include <algorithm>
#include <cstddef>

namespace eip2mqtt::adapters::mqtt::detail {

/// Whether a window of `limit` publications in flight, `pending` of them now, has room;
/// `was_full` when the sender last stopped at the limit.
inline bool has_room(std::size_t pending, std::size_t limit, bool was_full) {
    return pending + (was_full ? std::max<std::size_t>(1, limit / 8) : 1) <= limit;
}

/// Whether one more publication awaiting the broker's acknowledgement fits under `limit` (the
/// broker's Receive Maximum, or max_in_flight when lower), with `pending` of ours and `own` of
/// the client's own publications unacknowledged.
inline bool has_acknowledged_room(std::size_t pending, std::size_t own, std::size_t limit) {
    return pending + own < limit;
}

/// Windows of publications a backlog bound by the acknowledged window must outlast before the
/// connection counts as saturated: a burst (a pause of the machine, the first publication of
/// every tag) drains well within it.
inline constexpr std::size_t kSaturatedWindows = 8;

/// has_acknowledged_room on a saturated connection: two free slots, when the window has more
/// than two.
inline bool has_saturated_room(std::size_t pending, std::size_t own, std::size_t limit) {
    const std::size_t refill = limit > 2 ? 2 : 1;
    return pending + own + refill <= limit;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
