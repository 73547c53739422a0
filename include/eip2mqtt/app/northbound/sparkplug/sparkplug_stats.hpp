#pragma once
/// The Sparkplug edge node's own counters, apart from the node so that the metrics can name
/// them without it.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace eip2mqtt::app::northbound::sparkplug {

/// The edge node's session as it stands, for the status page (SparkplugNode::refresh_session).
struct SparkplugSession {
    std::string group_id;
    std::string edge_node_id;
    std::string primary_host_id;         ///< empty: the node publishes without waiting for a host
    bool host_online = false;            ///< the primary host's last STATE said online
    bool born = false;                   ///< NBIRTH published on this connection
    std::optional<std::uint8_t> bd_seq;  ///< of the session's will; none before the first
    std::size_t devices = 0;             ///< one per running exchange
    std::size_t devices_born = 0;        ///< DBIRTH published since the last NBIRTH
};

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
    SparkplugSession session;            ///< as of the last refresh_session()
};

}  // namespace eip2mqtt::app::northbound::sparkplug
