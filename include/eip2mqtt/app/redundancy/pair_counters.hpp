#pragma once
/// The counters of a hot-standby pair as the metrics topic's `pair` object reports them
/// (docs/schema/metrics.json): one table, which CounterNames compares with the schema.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "eip2mqtt/app/redundancy/pair_history.hpp"
#include "eip2mqtt/app/redundancy/pair_images.hpp"
#include "eip2mqtt/app/redundancy/pair_writes.hpp"
#include "eip2mqtt/core/counter_table.hpp"

namespace eip2mqtt::app::redundancy {

/// What the metrics topic's `pair` object reports: the images' counts, the datagrams of this
/// unit's own produced exchanges it heard (DatagramRouter: the other unit's, or its own looped
/// back), which is how a standby follows the request ids, the samples kept and replayed
/// across a takeover (PairHistory), what the unit had queued as leader and dropped once its
/// lease lapsed (the connection's ClientOptions::may_send), and the answers to writes: those
/// withheld or given late by a leader that stepped down, and those a standby heard or found
/// listed in the old leader's images (PairWrites).
struct PairCounters {
    PairImageCounters images;
    std::uint64_t produced_heard = 0;
    PairHistoryCounters history;
    std::uint64_t publications_fenced = 0;
    PairWriteCounters writes;
};

// clang-format off
inline constexpr std::array<core::GatewayCounterField<PairCounters>, 13> pair_counter_fields{{
    {"images_published", [](const PairCounters& c) { return core::one(c.images.published); },
     core::in_metrics_topic, ""},
    {"images_followed", [](const PairCounters& c) { return core::one(c.images.followed); },
     core::in_metrics_topic, ""},
    {"images_ignored",
     [](const PairCounters& c) { return std::span<const std::uint64_t>(c.images.ignored); },
     core::in_metrics_topic, "",
     [](std::size_t i) {
         constexpr std::array<std::string_view, 4> reasons{"other_layout", "stale",
                                                           "unknown_exchange", "not_an_image"};
         return reasons[i];
     }},
    {"produced_heard", [](const PairCounters& c) { return core::one(c.produced_heard); },
     core::in_metrics_topic, ""},
    {"samples_replayed", [](const PairCounters& c) { return core::one(c.history.replayed); },
     core::in_metrics_topic, ""},
    {"window_overflow",
     [](const PairCounters& c) { return core::one(c.history.window_overflow); },
     core::in_metrics_topic, ""},
    {"publications_fenced",
     [](const PairCounters& c) { return core::one(c.publications_fenced); },
     core::in_metrics_topic, ""},
    {"answers_withheld", [](const PairCounters& c) { return core::one(c.images.answers_withheld); },
     core::in_metrics_topic, ""},
    {"answers_late", [](const PairCounters& c) { return core::one(c.images.answers_late); },
     core::in_metrics_topic, ""},
    {"answers_heard", [](const PairCounters& c) { return core::one(c.writes.answers_heard); },
     core::in_metrics_topic, ""},
    {"answers_listed", [](const PairCounters& c) { return core::one(c.writes.answers_listed); },
     core::in_metrics_topic, ""},
    {"answers_repeated", [](const PairCounters& c) { return core::one(c.writes.answers_repeated); },
     core::in_metrics_topic, ""},
    {"left_writes_forgotten", [](const PairCounters& c) { return core::one(c.writes.forgotten); },
     core::in_metrics_topic, ""},
}};
// clang-format on

static_assert(core::counts_every_member<PairCounters>(pair_counter_fields),
              "every pair counter is read once by pair_counter_fields");

}  // namespace eip2mqtt::app::redundancy
