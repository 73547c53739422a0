#pragma once
/// CounterField: one counter of a counter set, declared once with its name and where it is
/// reported. A set's table (an array of them beside its struct) drives every report of it: the
/// `_status` payload or the metrics topic, the Prometheus families, the Sparkplug node metrics,
/// so that a name is written in one place and a new counter is a decision about each report.
/// An exchange's counters are CounterFields; the gateway's own sets (writes, commands), which
/// count some things per key (a reason, a request type), are GatewayCounterFields.
///
/// Threading: immutable constants; any thread.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace eip2mqtt::core {

/// Where a counter is reported; a field may be in several.
enum CounterReport : std::uint8_t {
    reported_nowhere = 0,
    in_status = 1,  ///< the exchange's `_status` (docs/schema/status.json), in table order
    /// `eip2mqtt_exchange_{name}_total`, or a gateway set's `eip2mqtt_{set}_{name}_total`
    /// (adapters/metrics)
    in_prometheus = 2,
    /// the node metric `Exchanges/{exchange}/{name}`, or a gateway set's `Gateway/{name}`
    in_sparkplug = 4,
    /// the gateway's metrics topic (docs/schema/metrics.json), in a set's object when it has a
    /// name, in table order
    in_metrics_topic = 8,
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

/// One counter of a gateway-wide set: a single count, or one count per key (a write error, a
/// request type), reported under one name: an object by key on the metrics topic, a Prometheus
/// sample per key labelled `label`, and the keys' sum as a Sparkplug node metric. Its counts are
/// read through a function rather than a member pointer, since they may be an array or a member
/// of a nested struct.
template <class Counters>
struct GatewayCounterField {
    std::string_view name;                                      ///< the same in every report
    std::span<const std::uint64_t> (*counts)(const Counters&);  ///< one count, or one per key
    std::uint8_t reports;                                       ///< CounterReport bits
    std::string_view help;                                      ///< Prometheus's HELP line
    /// The key of count `index`; an empty key leaves that count out of every report. Null for
    /// a single count.
    std::string_view (*key)(std::size_t index) = nullptr;
    std::string_view label = {};  ///< Prometheus's label for the key

    constexpr bool in(CounterReport report) const { return (reports & report) != 0; }
};

/// A single count, for a GatewayCounterField's `counts`.
constexpr std::span<const std::uint64_t> one(const std::uint64_t& count) { return {&count, 1}; }

/// Calls `visit(key, count)` for each count `field` reports of `counters`: once, with an empty
/// key, for a single count.
template <class Counters, class Visit>
void for_each_count(const GatewayCounterField<Counters>& field, const Counters& counters,
                    Visit&& visit) {
    const auto counts = field.counts(counters);
    if (field.key == nullptr) {
        visit(std::string_view{}, counts.front());
        return;
    }
    for (std::size_t i = 0; i < counts.size(); ++i) {
        if (const auto key = field.key(i); !key.empty()) visit(key, counts[i]);
    }
}

/// The sum of the counts `field` reports of `counters`.
template <class Counters>
std::uint64_t total(const GatewayCounterField<Counters>& field, const Counters& counters) {
    std::uint64_t sum = 0;
    for_each_count(field, counters,
                   [&sum](std::string_view, std::uint64_t count) { sum += count; });
    return sum;
}

/// True when `fields` read every count of `Counters` (std::uint64_t and arrays of them only,
/// maybe in nested structs), each once: for a static_assert beside the table.
template <class Counters, class Fields>
constexpr bool counts_every_member(const Fields& fields) {
    const Counters counters{};
    std::size_t read = 0;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const auto counts = fields[i].counts(counters);
        read += counts.size();
        for (std::size_t j = 0; j < i; ++j) {
            if (fields[j].counts(counters).data() == counts.data()) return false;
        }
    }
    return read * sizeof(std::uint64_t) == sizeof(Counters);
}

}  // namespace eip2mqtt::core
