#pragma once
/// The counters of one produced exchange and their table: the one place their names are
/// written (core/counter_table.hpp). Pure.

#include <array>
#include <cstdint>

#include "eip2mqtt/core/counter_table.hpp"

namespace eip2mqtt::core::exchange {

struct ProduceCounters {
    std::uint64_t sent = 0;
    std::uint64_t send_errors = 0;
    std::uint64_t skipped_deadlines = 0;  ///< periods lost because the loop fell behind
    std::uint64_t writes_applied = 0;
    std::uint64_t save_failures = 0;  ///< image saves that failed
};

using ProduceCounterField = CounterField<ProduceCounters>;

// clang-format off
inline constexpr std::array<ProduceCounterField, 5> produce_counter_fields{{
    {"sent", &ProduceCounters::sent, in_status | in_prometheus | in_sparkplug,
     "Datagrams produced"},
    {"send_errors", &ProduceCounters::send_errors, in_status | in_prometheus | in_sparkplug,
     "Productions the socket refused"},
    {"skipped_deadlines", &ProduceCounters::skipped_deadlines, in_status | in_prometheus,
     "Periods not produced because the loop fell more than a period behind"},
    {"writes_applied", &ProduceCounters::writes_applied, in_status | in_sparkplug,
     "Writes applied to the image"},
    {"save_failures", &ProduceCounters::save_failures, in_status | in_prometheus,
     "Image saves that failed"},
}};
// clang-format on

static_assert(covers_every_member<ProduceCounters>(produce_counter_fields),
              "every produce counter is listed once in produce_counter_fields");

}  // namespace eip2mqtt::core::exchange
