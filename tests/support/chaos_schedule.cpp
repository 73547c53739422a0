#include "tests/support/chaos_schedule.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "tools/fault_injector/fault_model.hpp"

namespace eip2mqtt::test {
namespace {

using std::chrono::milliseconds;

/// The draws both versions share: spans scaled to the takeover, and one fault.
class Draws {
public:
    Draws(std::uint64_t seed, milliseconds takeover) : rng_(seed), takeover_(takeover) {}

    milliseconds span(double from, double to) {
        const auto t = static_cast<double>(takeover_.count());
        return milliseconds(static_cast<long>(t * from + t * (to - from) * rng_.uniform()));
    }
    /// Version 1's draws, in its order: the kind among the first `kinds`, the unit, the length,
    /// the delay.
    ChaosFault fault(milliseconds at, std::size_t kinds) {
        ChaosFault fault;
        fault.at = at;
        fault.kind = static_cast<ChaosKind>(rng_.below(kinds));
        fault.unit = static_cast<int>(rng_.below(2));
        fault.length = fault.kind == ChaosKind::kill_unit ? milliseconds(0) : span(0.3, 3.0);
        if (fault.kind == ChaosKind::delay_broker) fault.delay = span(0.02, 0.12);
        return fault;
    }
    double uniform() { return rng_.uniform(); }

private:
    fault_injector::Rng rng_;
    milliseconds takeover_;
};

/// What a fault acts on: two faults on the same thing would undo each other's heal.
int resource(const ChaosFault& fault) {
    switch (fault.kind) {
        case ChaosKind::cut_unit:
        case ChaosKind::cut_broker:
            return fault.unit * 3;  // the unit's namespace
        case ChaosKind::stall_broker:
        case ChaosKind::delay_broker:
            return fault.unit * 3 + 1;  // its broker proxy
        case ChaosKind::stop_unit:
        case ChaosKind::kill_unit:
            return fault.unit * 3 + 2;  // its process
        case ChaosKind::stop_broker:
        case ChaosKind::kill_broker:
            return 6;
        case ChaosKind::forge:
            return 7;
    }
    return 7;
}

std::size_t most_faults(milliseconds duration, milliseconds takeover) {
    // A fault (or a pair) and its quiet spell take 3 takeovers at least.
    return static_cast<std::size_t>(duration / (3 * takeover)) + 1;
}

std::vector<ChaosFault> version_1(std::uint64_t seed, milliseconds duration,
                                  milliseconds takeover) {
    Draws draw(seed, takeover);
    std::vector<ChaosFault> out;
    auto at = draw.span(0.5, 1.5);
    const auto most = most_faults(duration, takeover);
    while (out.size() < most) {
        const auto fault = draw.fault(at, chaos_kinds_v1);
        if (at + fault.length > duration) break;
        out.push_back(fault);
        at += fault.length + draw.span(3.0, 4.0);
    }
    return out;
}

/// A second fault that begins while `first` is on, on something else; nullopt when the draws
/// find none in a bounded number of tries, or it would end after `duration`.
std::optional<ChaosFault> overlapping(Draws& draw, const ChaosFault& first, milliseconds duration) {
    const auto at =
        first.at + milliseconds(static_cast<long>(static_cast<double>(first.length.count()) *
                                                  (0.1 + 0.8 * draw.uniform())));
    for (int tries = 0; tries < 8; ++tries) {
        const auto second = draw.fault(at, chaos_kinds);
        if (resource(second) == resource(first) || second.kind == ChaosKind::kill_unit) continue;
        if (second.at + second.length > duration) return std::nullopt;
        return second;
    }
    return std::nullopt;
}

std::vector<ChaosFault> version_2(std::uint64_t seed, milliseconds duration,
                                  milliseconds takeover) {
    Draws draw(seed, takeover);
    std::vector<ChaosFault> out;
    auto at = draw.span(0.5, 1.5);
    const auto most = most_faults(duration, takeover);
    for (std::size_t groups = 0; groups < most; ++groups) {
        const auto fault = draw.fault(at, chaos_kinds);
        if (at + fault.length > duration) break;
        out.push_back(fault);
        auto end = at + fault.length;
        if (fault.length > milliseconds(0) && draw.uniform() < chaos_overlap_chance) {
            if (const auto second = overlapping(draw, fault, duration)) {
                out.push_back(*second);
                end = std::max(end, second->at + second->length);
            }
        }
        at = end + draw.span(3.0, 4.0);
    }
    return out;
}

}  // namespace

std::string to_string(ChaosKind kind) {
    static constexpr std::array<const char*, chaos_kinds> names{
        "cut_unit",  "cut_broker",  "stall_broker", "delay_broker", "stop_unit",
        "kill_unit", "stop_broker", "forge",        "kill_broker"};
    return names[static_cast<std::size_t>(kind)];
}

std::string ChaosFault::str() const {
    auto out = to_string(kind) + " at " + std::to_string(at.count()) + " ms for " +
               std::to_string(length.count()) + " ms";
    const bool broker = kind == ChaosKind::stop_broker || kind == ChaosKind::kill_broker;
    if (!broker) out += ", unit " + std::to_string(unit);
    if (kind == ChaosKind::delay_broker) out += ", delay " + std::to_string(delay.count()) + " ms";
    return out;
}

int chaos_schedule_version(std::uint64_t seed) { return seed < chaos_v2_first_seed ? 1 : 2; }

std::vector<ChaosFault> chaos_schedule(std::uint64_t seed, std::chrono::milliseconds duration,
                                       std::chrono::milliseconds takeover) {
    return chaos_schedule_version(seed) == 1 ? version_1(seed, duration, takeover)
                                             : version_2(seed, duration, takeover);
}

}  // namespace eip2mqtt::test
