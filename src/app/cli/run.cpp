// `eip2mqtt run -c FILE`: load and validate the configuration, then run the gateway.

#include <spdlog/spdlog.h>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"

namespace eip2mqtt::app {

int run_gateway(const RunOptions& options) {
    detail::keep_heap_thresholds();
    setup_logging(options.log_level.empty() ? "info" : options.log_level);
    auto loaded = adapters::yaml::load_config(options.config_path);
    if (!loaded) {
        for (const auto& diagnostic : loaded.error()) spdlog::error("{}", diagnostic.to_string());
        spdlog::critical("configuration {} has {} error(s); not starting", options.config_path,
                         loaded.error().size());
        return 1;
    }
    auto config = std::move(loaded).value();
    if (options.log_level.empty()) set_log_level(config.gateway.log_level);
    Gateway gateway(std::move(config));
    return gateway.run();
}

}  // namespace eip2mqtt::app
