// `eip2mqtt run -c FILE`: load and validate the configuration, then run the gateway.

#include <spdlog/spdlog.h>

#include "app/cli/detail/run_config.hpp"
#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"

namespace eip2mqtt::app {

std::optional<core::config::Config> detail::load_run_config(const RunOptions& options) {
    setup_logging(options.log_level.empty() ? "info" : options.log_level);
    auto loaded = adapters::yaml::load_config(options.config_path);
    if (!loaded) {
        for (const auto& diagnostic : loaded.error()) spdlog::error("{}", diagnostic.to_string());
        spdlog::critical("configuration {} has {} error(s); not starting", options.config_path,
                         loaded.error().size());
        return std::nullopt;
    }
    auto config = std::move(loaded).value();
    if (options.log_level.empty()) set_log_level(config.gateway.log_level);
    return config;
}

int run_gateway(const RunOptions& options) {
    detail::keep_heap_thresholds();
    auto config = detail::load_run_config(options);
    if (!config) return 1;
    Gateway gateway(std::move(*config));
    return gateway.run();
}

}  // namespace eip2mqtt::app
