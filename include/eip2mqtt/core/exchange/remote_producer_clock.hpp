#pragma once
/// Which time a consumed exchange's tags carry, and whether the producer's clock can be trusted.
/// A PLC without time synchronisation stamps its datagrams with its own clock (a
/// real capture reads the year 2000): published as is, a historian would file live values
/// decades in the past. Pure: the receive time is passed in.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::exchange {

/// The producer's clock as the last datagram showed it.
enum class ClockState : std::uint8_t {
    none,      ///< no datagram yet, or the last one had no timestamp (seconds 0)
    synced,    ///< within the tolerance of the receive time
    unsynced,  ///< beyond it
};

inline constexpr auto clock_state_names = enum_names<ClockState>("none", "synced", "unsynced");

constexpr std::string_view to_string(ClockState state) { return clock_state_names.name_of(state); }

class RemoteProducerClock {
public:
    RemoteProducerClock(plan::TimestampSource source, std::chrono::milliseconds tolerance);

    /// A datagram stamped `time_s` + `time_ns` (time_s 0: no timestamp) received at
    /// `receive_ms` (ms since 1970 UTC): updates the state and offset, and returns the
    /// timestamp its tags carry. `receive` always gives the receive time; `producer` the
    /// producer's time when there is one; `auto` the producer's time while the clock is
    /// synced. A timestamp never makes a datagram less acceptable.
    std::int64_t on_datagram(std::uint32_t time_s, std::uint32_t time_ns, std::int64_t receive_ms);

    ClockState state() const { return state_; }
    /// Producer time minus receive time of the last stamped datagram, in ms.
    std::optional<std::int64_t> offset_ms() const { return offset_ms_; }
    std::chrono::milliseconds tolerance() const { return tolerance_; }

private:
    plan::TimestampSource source_;
    std::chrono::milliseconds tolerance_;
    ClockState state_ = ClockState::none;
    std::optional<std::int64_t> offset_ms_;
};

}  // namespace eip2mqtt::core::exchange
