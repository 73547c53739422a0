#pragma once
/// A seeded schedule of faults for a hot-standby pair's chaos tests: cuts that tell neither end,
/// broker paths stalled or delayed, units and the broker stopped (SIGSTOP) or killed, forged
/// datagrams. Pure and deterministic: the same seed gives the same schedule on every machine
/// (the fault injector's SplitMix64), so a failing seed can be run again. Bounded in count and
/// in time.
///
/// Two versions, chosen by the seed, so that a seed names one schedule for ever (CI's seeds and
/// those a soak found keep the schedule they failed with):
/// - version 1, seeds below `chaos_v2_first_seed`: faults one at a time, each followed by a
///   quiet spell in which the pair settles; the broker is stopped, never killed. Its draws are
///   frozen: a new kind or option never changes a version 1 schedule
///   (tests/chaos/chaos_schedule_test.cpp pins the CI seeds').
/// - version 2, seeds from `chaos_v2_first_seed` on: every kind, `kill_broker` included; with a
///   probability of `chaos_overlap_chance`, a second fault begins while the first is still on.
///   The two touch different things (a unit's network, its broker proxy, its process, the
///   broker, the segment), and the second is never `kill_unit` (its restart waits for the unit
///   to say its role, which a fault of its path would hold back). The quiet spell follows both.

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
    kill_broker,   ///< SIGKILL of Mosquitto, started again on its port after `length` (v2 only)
};
inline constexpr std::size_t chaos_kinds = 9;
/// The kinds version 1 draws from: all but kill_broker.
inline constexpr std::size_t chaos_kinds_v1 = 8;
inline constexpr std::uint64_t chaos_v2_first_seed = 1000;
inline constexpr double chaos_overlap_chance = 0.4;
std::string to_string(ChaosKind kind);

struct ChaosFault {
    std::chrono::milliseconds at{0};      ///< since the schedule's start
    std::chrono::milliseconds length{0};  ///< until it heals
    ChaosKind kind = ChaosKind::cut_unit;
    int unit = 0;                        ///< 0 or 1 (the broker's faults ignore it)
    std::chrono::milliseconds delay{0};  ///< delay_broker only
    std::string str() const;
};

/// 1 or 2 (see above).
int chaos_schedule_version(std::uint64_t seed);

/// Faults for `duration`, from the seed, scaled to the pair's `takeover`, in the order they
/// begin: each lasts 0.3 to 3 takeovers (a delay stays under takeover / 8, within the lease's
/// assumptions), and is followed by at least 3 takeovers of quiet (version 2: the fault or the
/// overlapping pair).
std::vector<ChaosFault> chaos_schedule(std::uint64_t seed, std::chrono::milliseconds duration,
                                       std::chrono::milliseconds takeover);

}  // namespace eip2mqtt::test
