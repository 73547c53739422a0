#pragma once
/// What hosts send the edge node (docs/sparkplug.md): NCMD `Node Control/Rebirth`, DCMD (a
/// write to a produced exchange's tags) and the primary host's STATE. A DCMD is decoded into
/// one WriteRequest, refused or not, handed to the WriteHandler; a rebirth request and a change
/// of the host's STATE are told to the caller, which acts on them. What cannot be read is
/// logged, throttled.
///
/// Threading: the loop only.

#include <cstdint>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/northbound/sparkplug/device_registry.hpp"
#include "eip2mqtt/app/northbound/sparkplug/node_session.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

class NodeCommands {
public:
    /// `primary_host_id` empty: no STATE is taken. `writes` must outlive it; `origin` is the
    /// northbound every WriteRequest names for its result.
    NodeCommands(const std::string& group_id, const std::string& edge_node_id,
                 std::string primary_host_id, WriteHandler& writes, Northbound& origin);

    /// The topic filters to subscribe to: NCMD, every DCMD, and the primary host's STATE.
    std::vector<std::string> subscriptions() const;
    /// A new connection: the host's retained STATE comes again, whatever its timestamp.
    void connected() { host_state_timestamp_ = 0; }

    /// What a message asks of the node.
    enum class Asked {
        nothing,       ///< none, or a DCMD, handed to the WriteHandler already
        rebirth,       ///< NCMD `Node Control/Rebirth` true
        host_online,   ///< the primary host's STATE says online, and it was offline
        host_offline,  ///< it says offline, and it was online
    };
    /// NCMD, DCMD or the primary host's STATE; anything else is ignored. `session` says
    /// whether the node is born (a DCMD is refused `offline` until it is), what the host's last
    /// STATE said and the time.
    Asked on_message(const adapters::mqtt::Incoming& message, DeviceRegistry& devices,
                     const NodeSession& session);

    /// The summaries of throttled logs due at `now`.
    void flush_logs(core::MonoTime now, std::uint64_t node_births, bool host_online);

private:
    Asked on_node_command(const adapters::mqtt::Incoming& message, core::MonoTime now);
    /// A DCMD for `device` (nullptr: no exchange of that name): one WriteRequest, refused or not.
    void on_device_command(const adapters::mqtt::Incoming& message, const Device* device,
                           const NodeSession& session);
    Asked on_state(const adapters::mqtt::Incoming& message, const NodeSession& session);
    Asked host_changed(bool online, core::MonoTime now);

    std::string ncmd_topic_, dcmd_prefix_, state_topic_;
    std::string primary_host_id_;
    WriteHandler& writes_;
    Northbound& origin_;
    std::int64_t host_state_timestamp_ = 0;  ///< of the last STATE taken: older ones are stale
    core::ThrottledLog command_log_;         ///< NCMD and STATE that cannot be read
    core::ThrottledLog rebirth_log_;         ///< NCMD rebirth requests
    core::ThrottledLog state_log_;           ///< the primary host's STATE changes
    core::ThrottledLog refused_log_;         ///< DCMD refused while the node is not born
};

}  // namespace eip2mqtt::app::northbound::sparkplug
