#pragma once
/// The wall-clock time a produced datagram carries: the UTC time of the deadline it serves,
/// not of the moment the loop got round to it. A consumer then sees steps of whole periods
/// (skipped deadlines make whole multiples), however busy the machine was, as a PLC's
/// scan-synchronous stamps do. Deadlines are monotonic, so they are mapped to UTC through one
/// anchor (a reading of both clocks); the anchor is taken again only when the wall clock moved
/// against the monotonic one by more than a tolerance (a clock step, or NTP slewing long
/// enough), so that stamps never stray further than that from the system's UTC. Pure: both
/// clocks are read by the caller.

#include <chrono>
#include <cstdint>
#include <optional>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class SamplingClock {
public:
    /// How far the wall clock may move against the monotonic one before re-anchoring.
    static constexpr std::chrono::milliseconds default_tolerance{20};

    explicit SamplingClock(std::chrono::nanoseconds tolerance = default_tolerance)
        : tolerance_(tolerance) {}

    /// Records a reading of both clocks taken together; anchors on the first one, and again
    /// when the offset between them moved by more than the tolerance.
    void observe(MonoTime mono, WallTime wall);

    /// The UTC time of monotonic time `t`; observe() must have been called once.
    WallTime to_wall(MonoTime t) const;

    /// How many times the anchor was taken again after the first.
    std::uint64_t reanchors() const { return reanchors_; }

private:
    std::chrono::nanoseconds tolerance_;
    /// wall - mono at the anchor, in nanoseconds since each clock's epoch.
    std::optional<std::chrono::nanoseconds> offset_;
    std::uint64_t reanchors_ = 0;
};

}  // namespace eip2mqtt::core::exchange
