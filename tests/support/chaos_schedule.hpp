#pragma once
/// A seeded schedule of faults for a hot-standby pair's chaos tests: cuts that tell neither end,
/// broker paths stalled or delayed, units and the broker stopped (SIGSTOP) or killed, forged
/// datagrams. Pure and deterministic: the same seed gives the same schedule on every machine
/// (the fault injector's SplitMix64), so a failing seed can be run again. Bounded: faults come
/// one at a time, each followed by a quiet spell in which the pair settles, until `duration`.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace eip2mqtt::test {

enum class ChaosKind : std::uint8_t {
    cut_unit,      ///< iptables DROP of everything in and out of a unit's namespace
    cut_broker,    ///< iptables DROP of the unit's TCP only: datagrams still pass
    stall_broker,  ///< the unit's broker proxy holds both directions, then delivers all at once
    delay_broker,  ///< the unit's broker proxy delays both directions by `delay`
    stop_unit,     ///< SIGSTOP, then SIGCONT
    kill_unit,     ///< SIGKILL, then started again
    stop_broker,   ///< SIGSTOP of Mosquitto, then SIGCONT
    forge,         ///< datagrams from a forged source address, on raw sockets
};
inline constexpr std::size_t chaos_kinds = 8;
std::string to_string(ChaosKind kind);

struct ChaosFault {
    std::chrono::milliseconds at{0};      ///< since the schedule's start
    std::chrono::milliseconds length{0};  ///< until it heals
    ChaosKind kind = ChaosKind::cut_unit;
    int unit = 0;                        ///< 0 or 1 (the broker's faults ignore it)
    std::chrono::milliseconds delay{0};  ///< delay_broker only
    std::string str() const;
};

/// Faults for `duration`, from the seed, scaled to the pair's `takeover`: each lasts 0.3 to 3
/// takeovers (a delay stays under takeover / 8, within the lease's assumptions), and is
/// followed by at least 3 takeovers of quiet.
std::vector<ChaosFault> chaos_schedule(std::uint64_t seed, std::chrono::milliseconds duration,
                                       std::chrono::milliseconds takeover);

}  // namespace eip2mqtt::test
