#include "eip2mqtt/app/reload/reload_check.hpp"

#include <spdlog/spdlog.h>

#include <string>

namespace eip2mqtt::app::reload {

using core::config::ReloadRule;

std::optional<core::config::ReloadPlan> accept(
    const ParseResult& parsed, const core::config::Config& running,
    std::span<const core::plan::ExchangePlan* const> running_plans) {
    if (!parsed) {
        for (const auto& diagnostic : parsed.error()) spdlog::error("{}", diagnostic.to_string());
        spdlog::error("reload refused: {} has {} error(s); the running configuration is kept",
                      running.file, parsed.error().size());
        return std::nullopt;
    }
    const auto& next = parsed.value();
    auto changes = core::config::plan_reload(running, running_plans, next.config, next.plans);
    if (changes.needs_restart) {
        const auto restart = changes.describe(ReloadRule::restart);
        const auto live = changes.describe(ReloadRule::live);
        spdlog::error(
            "reload refused: {} {} a restart (systemctl restart eip2mqtt); nothing is applied{}; "
            "the running configuration is kept",
            restart, restart.find(", ") == std::string::npos ? "needs" : "need",
            live.empty() ? "" : " (also changed: " + live + ")");
        return std::nullopt;
    }
    return changes;
}

}  // namespace eip2mqtt::app::reload
