#pragma once
/// The Sparkplug edge node's own counters, apart from the node so that the metrics can name
/// them without it.

#include <cstdint>

namespace eip2mqtt::app::northbound::sparkplug {

/// What the node counts beyond the gateway's counters: the node metrics `Sparkplug/...` and
/// the metrics topic's `sparkplug`.
struct SparkplugStats {
    /// NBIRTH or DBIRTH over the largest packet the broker takes: not published, so the node or
    /// that device is not born.
    std::uint64_t births_refused = 0;
    /// DDATA or NDATA over it (a device's DDATA is smaller than its DBIRTH: never, in practice).
    std::uint64_t data_refused = 0;
    std::uint64_t rebirth_requests = 0;  ///< NCMD `Node Control/Rebirth` taken
    std::uint64_t node_births = 0;       ///< NBIRTHs published
};

}  // namespace eip2mqtt::app::northbound::sparkplug
