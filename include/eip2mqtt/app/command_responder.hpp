#pragma once
/// The responder of the command protocol on UDP 7937 (docs/protocol.md §9; README
/// "Commissioning"): answers each request from a source in `allow`, within the rate limit, from
/// views of the running exchanges taken when it comes. Writes (with `writes: true`) become one
/// WriteRequest each, for the same WriteHandler as MQTT writes, and are answered when their
/// result comes back: once the datagram carrying them has left and the image is saved. Nothing
/// is ever sent but a response to the requester's address and port. No socket: the caller
/// feeds datagrams in and sends what comes out, so it is tested without one.
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/app/northbound.hpp"
#include "eip2mqtt/core/command/answer.hpp"
#include "eip2mqtt/core/command/command_counters.hpp"
#include "eip2mqtt/core/command/subnet.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/write/rate_limiter.hpp"

namespace eip2mqtt::app {

/// Who is answered, how often, and whether writes are: eip.commands, live on reload.
struct CommandPolicy {
    std::vector<core::command::Subnet> allow;  ///< resolved: never empty in a running gateway
    bool writes = false;
    std::uint32_t max_requests_per_s = 100;
};

/// eip.commands of `config` as a responder applies it: `allow` resolved to the subnets of
/// eip.bind's interfaces when empty (adapters::udp::local_subnets).
CommandPolicy command_policy(const core::config::Config& config);

class CommandResponder final : public Northbound {
public:
    /// The exchanges as they are at `now`: views borrowed until the next call.
    using Views = std::function<std::vector<core::command::ExchangeView>(core::MonoTime now,
                                                                         core::WallTime wall)>;
    /// Sends a datagram to a requester; false when the kernel refused it.
    using Send =
        std::function<bool(std::span<const std::byte> datagram, const adapters::udp::Endpoint& to)>;

    /// `writes` takes the writes (nullptr: none are ever staged, whatever the policy says);
    /// `node.writes` is taken from the policy.
    CommandResponder(CommandPolicy policy, core::command::NodeInfo node, Views views, Send send,
                     WriteHandler* writes);

    /// One datagram received on the command port.
    void on_datagram(std::span<const std::byte> datagram, const adapters::udp::Endpoint& from,
                     core::MonoTime now, core::WallTime wall);

    /// A reload's new policy; writes waiting for their result are still answered.
    void set_policy(CommandPolicy policy);

    /// The summary of refusals, drops and NAKs that stopped coming, which no next one would log
    /// (the gateway's tick).
    void flush_log(core::MonoTime now);

    const core::command::CommandCounters& counters() const { return counters_; }
    std::size_t pending_writes() const { return pending_.size(); }

    // --- Northbound: only write results concern the responder ----------------------------
    void write_result(const WriteReply& reply, std::optional<std::string_view> error) override;

private:
    struct PendingWrite {
        core::command::Request request;
        adapters::udp::Endpoint to;
    };

    /// Most writes waiting for their datagram at once; beyond, a write is refused at once.
    static constexpr std::size_t max_pending = 256;

    void answer(core::command::Request request, const adapters::udp::Endpoint& from,
                core::MonoTime now, core::WallTime wall);
    void stage(core::command::Request request, core::command::StageWrites writes,
               const adapters::udp::Endpoint& from);
    void reply(std::span<const std::byte> response, const adapters::udp::Endpoint& to);
    void log(std::string_view what, const adapters::udp::Endpoint& from, core::MonoTime now);
    void log_summary(std::uint64_t count) const;

    CommandPolicy policy_;
    core::command::NodeInfo node_;
    Views views_;
    Send send_;
    WriteHandler* writes_;
    core::write::RateLimiter limiter_;
    core::command::CommandCounters counters_;
    std::unordered_map<std::uint64_t, PendingWrite> pending_;
    std::uint64_t next_write_ = 1;
    /// Set while a write is handed to the WriteHandler: a result then is a refusal.
    bool staging_ = false;
    core::ThrottledLog log_;
};

}  // namespace eip2mqtt::app
