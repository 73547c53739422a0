#pragma once
/// The counters of one consumed exchange and their table: the one place their names are
/// written (core/counter_table.hpp). Pure.

#include <array>
#include <cstdint>

#include "eip2mqtt/core/counter_table.hpp"

namespace eip2mqtt::core::exchange {

struct ConsumeCounters {
    std::uint64_t received = 0;  ///< datagrams for this exchange, whatever became of them
    std::uint64_t accepted = 0;
    std::uint64_t missed = 0;  ///< request ids skipped between two accepted samples
    std::uint64_t duplicates = 0;
    std::uint64_t out_of_order = 0;
    std::uint64_t signature_mismatches = 0;
    std::uint64_t length_mismatches = 0;
    std::uint64_t no_data = 0;
    std::uint64_t timeouts = 0;  ///< times the exchange went stale
    /// Producer restarts: a request id that looks old with a producer time that moved forward.
    std::uint64_t restarts = 0;
    /// Datagrams refused because they came from another address than `source` (not counted
    /// in `received`: the exchange never saw them).
    std::uint64_t wrong_source = 0;
    /// Publications of scaled tags whose raw value lay beyond the scale's raw range (those
    /// flagged "limit"): a transmitter out of its range, or a scale that does not fit it.
    std::uint64_t beyond_raw_range = 0;
};

using ConsumeCounterField = CounterField<ConsumeCounters>;

// clang-format off
inline constexpr std::array<ConsumeCounterField, 12> consume_counter_fields{{
    {"received", &ConsumeCounters::received, in_status | in_prometheus | in_sparkplug,
     "Datagrams received for the exchange"},
    {"accepted", &ConsumeCounters::accepted, in_status | in_prometheus | in_sparkplug,
     "Datagrams accepted as new samples"},
    {"missed", &ConsumeCounters::missed, in_status | in_prometheus | in_sparkplug,
     "Request ids skipped between accepted samples"},
    {"duplicates", &ConsumeCounters::duplicates, in_status | in_prometheus,
     "Datagrams repeating the last request id"},
    {"out_of_order", &ConsumeCounters::out_of_order, in_status | in_prometheus,
     "Datagrams behind the last request id"},
    {"signature_mismatches", &ConsumeCounters::signature_mismatches, in_status | in_prometheus,
     "Datagrams with an incompatible signature"},
    {"length_mismatches", &ConsumeCounters::length_mismatches, in_status | in_prometheus,
     "Datagrams with another data length than configured"},
    // Datagrams with a header and no data: counted with the gateway's drops (`no_data`).
    {"no_data", &ConsumeCounters::no_data, reported_nowhere, ""},
    {"timeouts", &ConsumeCounters::timeouts, in_status | in_sparkplug,
     "Times the exchange went stale"},
    {"restarts", &ConsumeCounters::restarts, in_status | in_prometheus | in_sparkplug,
     "Producer restarts (request ids started again while the producer's time went on)"},
    {"wrong_source", &ConsumeCounters::wrong_source, in_prometheus,
     "Datagrams from another address than the configured source"},
    {"beyond_raw_range", &ConsumeCounters::beyond_raw_range, in_status | in_prometheus,
     "Publications of scaled tags whose raw value lay beyond the scale's raw range"},
}};
// clang-format on

static_assert(covers_every_member<ConsumeCounters>(consume_counter_fields),
              "every consume counter is listed once in consume_counter_fields");

}  // namespace eip2mqtt::core::exchange
