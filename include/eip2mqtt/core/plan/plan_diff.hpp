#pragma once
/// What a reload does to the running exchanges, decided without running any: an exchange whose
/// plan is unchanged keeps running as it is (its sequence, image and sockets), a new or changed
/// one starts, a removed or changed one stops, and the retained topics that only stopped
/// exchanges published are cleared, so that no subscriber keeps reading a tag that is gone.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::plan {

struct PlanDiff {
    /// For each plan of `next`, in order: the index in `running` of the exchange it keeps, or
    /// nullopt when it starts.
    std::vector<std::optional<std::size_t>> kept_from;
    std::vector<std::size_t> stopped;  ///< indices in `running`, in order
    std::vector<std::string> cleared;  ///< retained topics to clear, sorted
};

/// Exchanges are matched by name. The topics of `next` are gathered only when some exchange
/// stops: a set of every tag topic costs a string per tag.
PlanDiff diff_plans(std::span<const ExchangePlan* const> running,
                    std::span<const ExchangePlan> next);

/// The exchanges a diff names, for the reload's log: `kept a, b; changed c; started d; stopped
/// e` (parts with no exchange left out, `nothing` when all are empty). A changed exchange is
/// one stopped and started again under its name. Each part lists at most `max_names`, then
/// `and N more`.
std::string describe_diff(const PlanDiff& diff, std::span<const ExchangePlan* const> running,
                          std::span<const ExchangePlan> next, std::size_t max_names = 20);

}  // namespace eip2mqtt::core::plan
