#pragma once
/// What `run` (run.cpp) does before the gateway starts: logging set up at the level asked for,
/// the configuration loaded and checked.

#include <optional>

#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app::detail {

/// Sets up logging at `options.log_level`, else at info and then at gateway.log_level of the
/// configuration once loaded. nullopt when the configuration has errors, each logged, then the
/// refusal to start.
std::optional<core::config::Config> load_run_config(const RunOptions& options);

}  // namespace eip2mqtt::app::detail
