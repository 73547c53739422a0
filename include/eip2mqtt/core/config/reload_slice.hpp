#pragma once
/// How much of a reload's publishing one turn of the loop takes (docs/reliability.md: a reload
/// that adds or removes a plant never stops the loop for much longer than a tick). Applying a
/// reload publishes in slices, the loop receiving and producing between two: clearing the
/// retained topics of removed exchanges and describing the new ones (app/reload.cpp).

#include <cstddef>

namespace eip2mqtt::core::config {

/// The publish queue of the connection a reload publishes on, as it is now.
struct PublishQueueRoom {
    std::size_t queued = 0;    ///< publications waiting, every lane
    std::size_t capacity = 0;  ///< mqtt.buffer.max_messages
    bool connected = false;    ///< the queue drains
};

/// Work units (one per publication, more for a costlier one) of one slice.
inline constexpr std::size_t reload_slice_units = 1000;

/// The units the next slice may take: at most `units`, and while the queue drains no more
/// publications than fill half of it, so that none is dropped for overflow (the queue drops
/// its oldest when full) and live values keep room. 0: wait for the queue to drain. While
/// disconnected the queue keeps what it can hold, as for any publication: waiting for a
/// connection would hold the reload up for as long as the broker is away.
std::size_t slice_units(std::size_t units, const PublishQueueRoom& room);

}  // namespace eip2mqtt::core::config
