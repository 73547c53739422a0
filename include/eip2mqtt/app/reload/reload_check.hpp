#pragma once
/// Whether a reloaded file may be applied to the running gateway (docs/operations.md, Reload):
/// not when it has errors, nor when it changes a key that only a restart applies
/// (core::config::plan_reload). Each refusal is logged once, naming the file's errors or the
/// keys, and saying that the running configuration is kept.

#include <optional>
#include <span>

#include "eip2mqtt/app/reload/reload_worker.hpp"
#include "eip2mqtt/core/config/reload_plan.hpp"

namespace eip2mqtt::app::reload {

/// The changes `parsed` makes to `running` (whose exchanges run `running_plans`), or nullopt,
/// logged, when it is refused.
std::optional<core::config::ReloadPlan> accept(
    const ParseResult& parsed, const core::config::Config& running,
    std::span<const core::plan::ExchangePlan* const> running_plans);

}  // namespace eip2mqtt::app::reload
