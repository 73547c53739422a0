#pragma once
/// The status API's documents (docs/operations.md, "Status API"): what the gateway, its
/// connections and each exchange are doing, as JSON. Each exchange's `status` is its `_status`
/// payload and each tag's sample its JSON payload, built by the same code as the MQTT topics, so
/// the page and the topics never disagree.
///
/// Threading: the loop only (they read the exchanges as they stand).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/exchanges/write_log.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/status/sparklines.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::status {

/// What /api/status says of the gateway besides its metrics.
struct GatewayFacts {
    std::string id;
    std::string config_file;
    std::vector<std::string> brokers;  ///< mqtt.url's list, in order
    core::WallTime started_at;
    core::MonoTime started_mono;
    /// When the running configuration took effect: the start, or the last reload applied.
    core::WallTime loaded_at;
    std::uint64_t reloads = 0;
};

/// GET /api/status (docs/schema/api-status.json): the gateway, then every exchange in one
/// line each, without its tags; then, when given, the last writes (newest first) and the last
/// warnings of the log (oldest first).
std::string status_document(const GatewayFacts& facts, const MetricsSources& sources,
                            const Exchanges& exchanges, core::MonoTime now, core::WallTime wall,
                            const WriteLog* writes = nullptr,
                            std::span<const std::string> warnings = {});

/// GET /api/exchanges/{name} (docs/schema/api-exchange.json): the exchange's line and each of
/// its tags with its value; nullopt when no exchange has that name.
/// With `sparklines`, each numeric tag that has one carries it (`sparkline`).
std::optional<std::string> exchange_document(const Exchanges& exchanges, std::string_view name,
                                             core::MonoTime now, core::WallTime wall,
                                             const Sparklines* sparklines = nullptr);

}  // namespace eip2mqtt::app::status
