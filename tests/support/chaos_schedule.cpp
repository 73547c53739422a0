#include "tests/support/chaos_schedule.hpp"

#include <array>

#include "tools/fault_injector/fault_model.hpp"

namespace eip2mqtt::test {

std::string to_string(ChaosKind kind) {
    static constexpr std::array<const char*, chaos_kinds> names{
        "cut_unit",  "cut_broker", "stall_broker", "delay_broker",
        "stop_unit", "kill_unit",  "stop_broker",  "forge"};
    return names[static_cast<std::size_t>(kind)];
}

std::string ChaosFault::str() const {
    auto out = to_string(kind) + " at " + std::to_string(at.count()) + " ms for " +
               std::to_string(length.count()) + " ms";
    if (kind != ChaosKind::stop_broker) out += ", unit " + std::to_string(unit);
    if (kind == ChaosKind::delay_broker) out += ", delay " + std::to_string(delay.count()) + " ms";
    return out;
}

std::vector<ChaosFault> chaos_schedule(std::uint64_t seed, std::chrono::milliseconds duration,
                                       std::chrono::milliseconds takeover) {
    using std::chrono::milliseconds;
    fault_injector::Rng rng(seed);
    const auto span = [&](double from, double to) {
        const auto t = static_cast<double>(takeover.count());
        return milliseconds(static_cast<long>(t * from + t * (to - from) * rng.uniform()));
    };
    std::vector<ChaosFault> out;
    auto at = span(0.5, 1.5);
    // Bounded in count as well as in time: a fault and its quiet spell take 3 takeovers at least.
    const auto most = static_cast<std::size_t>(duration / (3 * takeover)) + 1;
    while (out.size() < most) {
        ChaosFault fault;
        fault.at = at;
        fault.kind = static_cast<ChaosKind>(rng.below(chaos_kinds));
        fault.unit = static_cast<int>(rng.below(2));
        fault.length = fault.kind == ChaosKind::kill_unit ? milliseconds(0) : span(0.3, 3.0);
        if (fault.kind == ChaosKind::delay_broker) fault.delay = span(0.02, 0.12);
        if (at + fault.length > duration) break;
        out.push_back(fault);
        at += fault.length + span(3.0, 4.0);
    }
    return out;
}

}  // namespace eip2mqtt::test
