#pragma once
/// What a reload changes, decided before anything is applied: every key whose value differs
/// between the running configuration and the next, named by its YAML path, with its rule
/// (config_keys.hpp). A reload applies every change or, when one needs a restart, none.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/config_keys.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::config {

std::string_view to_string(ReloadRule rule);

struct KeyChange {
    enum class Kind : std::uint8_t { changed, added, removed };

    /// The YAML path: `mqtt.batch_first`, `eip.multicast`, `exchanges[turbine1].period_ms`,
    /// `exchanges[turbine1].tags[SPEED].deadband`; an exchange or a tag added or removed is
    /// `exchanges[turbine1]`, `exchanges[turbine1].tags[SPEED]`.
    std::string key;
    ReloadRule rule = ReloadRule::live;
    Kind kind = Kind::changed;

    friend bool operator==(const KeyChange&, const KeyChange&) = default;
};

struct ReloadPlan {
    /// At most this many changes are named: a new point list may change 100,000 tags, and one
    /// log line names them.
    static constexpr std::size_t max_named = 50;

    std::vector<KeyChange> changes;  ///< in file order: the sections, then the exchanges
    std::size_t unnamed = 0;         ///< changes beyond max_named
    bool needs_restart = false;      ///< some change, named or not, is ReloadRule::restart

    bool empty() const { return changes.empty() && unnamed == 0; }
    /// The changes with `rule`, for a log line: `mqtt.url, exchanges[a] (added)`, then
    /// `and N more` when some went unnamed (those are all live: sections come first).
    std::string describe(ReloadRule rule) const;
};

/// Compares `running` with `next`. The exchanges are compared by their plans (the gateway keeps
/// plans, not exchange configs, once running), matched by name; `running_exchanges` and
/// `next_exchanges` are those of the two configurations (spec.tags may be empty: the tags are
/// read from ExchangePlan::tags).
ReloadPlan plan_reload(const Config& running,
                       std::span<const plan::ExchangePlan* const> running_exchanges,
                       const Config& next, std::span<const plan::ExchangePlan> next_exchanges);

}  // namespace eip2mqtt::core::config
