#pragma once
/// CounterField: one counter of a counter set, declared once with its name and where it is
/// reported. A set's table (an array of them beside its struct) drives every report of it: the
/// `_status` payload, the Prometheus families, the Sparkplug node metrics, so that a name is
/// written in one place and a new counter is a decision about each report.
///
/// Threading: immutable constants; any thread.

#include <cstdint>
#include <string_view>

namespace eip2mqtt::core {

/// Where a counter is reported; a field may be in several.
enum CounterReport : std::uint8_t {
    reported_nowhere = 0,
    in_status = 1,      ///< the exchange's `_status` (docs/schema/status.json), in table order
    in_prometheus = 2,  ///< `eip2mqtt_exchange_{name}_total` (adapters/metrics)
    in_sparkplug = 4,   ///< the node metric `Exchanges/{exchange}/{name}`
};

template <class Counters>
struct CounterField {
    std::string_view name;  ///< the same in every report
    std::uint64_t Counters::*member;
    std::uint8_t reports;   ///< CounterReport bits
    std::string_view help;  ///< Prometheus's HELP line

    constexpr bool in(CounterReport report) const { return (reports & report) != 0; }
};

/// True when `fields` lists every counter of `Counters` (a struct of std::uint64_t only), each
/// once: for a static_assert beside the table.
template <class Counters, class Fields>
constexpr bool covers_every_member(const Fields& fields) {
    if (fields.size() * sizeof(std::uint64_t) != sizeof(Counters)) return false;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        for (std::size_t j = i + 1; j < fields.size(); ++j) {
            if (fields[i].member == fields[j].member) return false;
        }
    }
    return true;
}

}  // namespace eip2mqtt::core
