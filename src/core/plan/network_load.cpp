#include "eip2mqtt/core/plan/network_load.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace eip2mqtt::core::plan {

namespace {

Rate rate_of(const ExchangePlan& plan) {
    const std::chrono::nanoseconds period = plan.spec.period;
    if (period.count() <= 0) return {};
    const double datagrams_per_s = 1e9 / static_cast<double>(period.count());
    return {datagrams_per_s, datagrams_per_s * static_cast<double>(wire_bytes(plan.length) * 8)};
}

}  // namespace

NetworkLoad network_load(const std::vector<ExchangePlan>& plans) {
    const auto produced = static_cast<std::int64_t>(std::count_if(
        plans.begin(), plans.end(),
        [](const ExchangePlan& plan) { return plan.spec.direction == Direction::produce; }));
    NetworkLoad load;
    std::int64_t index = 0;
    for (const auto& plan : plans) {
        if (plan.spec.direction != Direction::produce) continue;
        const std::chrono::nanoseconds period = plan.spec.period;
        const auto rate = rate_of(plan);
        ExchangeLoad exchange{plan.spec.name, plan.spec.destination, rate.datagrams_per_s,
                              rate.bits_per_s,
                              std::chrono::nanoseconds{period.count() * index / produced}};
        ++index;
        auto to = std::find_if(
            load.destinations.begin(), load.destinations.end(),
            [&](const DestinationLoad& d) { return d.destination == exchange.destination; });
        if (to == load.destinations.end()) {
            DestinationLoad destination;
            destination.destination = exchange.destination;
            to = load.destinations.insert(load.destinations.end(), std::move(destination));
        }
        ++to->exchanges;
        to->datagrams_per_s += exchange.datagrams_per_s;
        to->bits_per_s += exchange.bits_per_s;
        load.datagrams_per_s += exchange.datagrams_per_s;
        load.bits_per_s += exchange.bits_per_s;
        load.exchanges.push_back(std::move(exchange));
    }
    return load;
}

Rate configured_rate(const std::vector<ExchangePlan>& plans) {
    Rate total;
    for (const auto& plan : plans) {
        const auto rate = rate_of(plan);
        total.datagrams_per_s += rate.datagrams_per_s;
        total.bits_per_s += rate.bits_per_s;
    }
    return total;
}

}  // namespace eip2mqtt::core::plan
