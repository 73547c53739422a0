#pragma once
/// What the gateway counts of the writes it handles, and their table: the one place their names
/// are written (core/counter_table.hpp). Pure.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "eip2mqtt/core/counter_table.hpp"
#include "eip2mqtt/core/write/write_origin.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::write {

/// What the image saves of every produced exchange add up to, kept by the gateway: a reload
/// replaces producers and their counters, never these.
struct ImageSaveTotals {
    std::uint64_t failures = 0;  ///< image saves that failed
    /// Accepted writes refused because the save that had to precede them failed (`not saved`).
    std::uint64_t writes_not_saved = 0;
    /// Writes sent, whose save then failed (`"saved":false`).
    std::uint64_t writes_sent_unsaved = 0;
};

struct WriteCounters {
    std::uint64_t writes_ok = 0;  ///< writes staged for production
    std::array<std::uint64_t, write_error_count> writes_rejected{};
    /// Of writes_ok, those still queued when a reload changed or removed their exchange:
    /// answered `"reloaded"`, never produced.
    std::uint64_t writes_cancelled = 0;
    /// Writes a standby of a pair dropped unanswered, because its live leader answers them.
    std::uint64_t writes_left_to_leader = 0;
    /// Of those, writes a unit settled as it took the lead, its old leader's answer unheard:
    /// taken, the image holding what they wrote, or refused `standby`.
    std::uint64_t writes_settled_applied = 0;
    std::uint64_t writes_settled_standby = 0;
    /// Image saves of every produced exchange, and the writes whose save failed.
    ImageSaveTotals image_saves;
    /// Of writes_ok, by the protocol they came by (WriteOrigin).
    std::array<std::uint64_t, write_origin_count> writes_by_origin{};
};

using WriteCounterField = GatewayCounterField<WriteCounters>;

// clang-format off
inline constexpr std::array<WriteCounterField, 10> write_counter_fields{{
    {"writes_ok", [](const WriteCounters& c) { return one(c.writes_ok); },
     in_metrics_topic | in_prometheus | in_sparkplug, "Writes accepted"},
    {"writes_rejected",
     [](const WriteCounters& c) { return std::span<const std::uint64_t>(c.writes_rejected); },
     in_metrics_topic | in_prometheus | in_sparkplug, "Writes rejected, by reason",
     [](std::size_t i) { return to_string(static_cast<WriteError>(i)); }, "reason"},
    {"writes_cancelled", [](const WriteCounters& c) { return one(c.writes_cancelled); },
     in_metrics_topic | in_prometheus,
     "Writes accepted, then cancelled unproduced: a reload changed or removed their exchange"},
    {"writes_left_to_leader", [](const WriteCounters& c) { return one(c.writes_left_to_leader); },
     in_metrics_topic, ""},
    {"writes_settled_applied", [](const WriteCounters& c) { return one(c.writes_settled_applied); },
     in_metrics_topic, ""},
    {"writes_settled_standby", [](const WriteCounters& c) { return one(c.writes_settled_standby); },
     in_metrics_topic, ""},
    {"writes_not_saved",
     [](const WriteCounters& c) { return one(c.image_saves.writes_not_saved); },
     in_metrics_topic | in_prometheus,
     "Writes accepted, then refused unproduced: the save that had to precede them failed"},
    {"writes_sent_unsaved",
     [](const WriteCounters& c) { return one(c.image_saves.writes_sent_unsaved); },
     in_metrics_topic | in_prometheus,
     "Writes sent, whose image save then failed: a restart would undo them until the next "
     "successful save"},
    {"image_save_failures", [](const WriteCounters& c) { return one(c.image_saves.failures); },
     in_metrics_topic | in_prometheus, "Image saves of produced exchanges that failed"},
    {"writes_by_origin",
     [](const WriteCounters& c) { return std::span<const std::uint64_t>(c.writes_by_origin); },
     in_metrics_topic | in_prometheus, "Writes accepted, by the protocol they came by",
     [](std::size_t i) { return to_string(static_cast<WriteOrigin>(i)); }, "origin"},
}};
// clang-format on

static_assert(counts_every_member<WriteCounters>(write_counter_fields),
              "every write counter is read once by write_counter_fields");

}  // namespace eip2mqtt::core::write
