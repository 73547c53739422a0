#pragma once
/// The responder of the command protocol on UDP 7937 (docs/protocol.md §9;
/// docs/commissioning.md): answers each request from a source in `allow`, within the rate limits
/// (per source, then overall: one budget for requesters that proved their address, one for those
/// that did not), from views of the running exchanges taken when it comes. A requester that has
/// not proved its address (§9.7) and is not `trusted` never gets more bytes than it sent, and
/// its writes are not taken: it gets a challenge with the token to ask again with. Writes (with
/// `writes: true`) become one WriteRequest each, for the same WriteHandler as MQTT writes, and are
/// answered when their result comes back: once the datagram carrying them has left and the image is
/// saved. Nothing is ever sent but a response to the requester's address and port. No socket: the
/// caller feeds datagrams in and sends what comes out, so it is tested without one.
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/command/address_proof.hpp"
#include "eip2mqtt/core/command/answer.hpp"
#include "eip2mqtt/core/command/command_counters.hpp"
#include "eip2mqtt/core/command/source_limiter.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/net/subnet.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/write/rate_limiter.hpp"

namespace eip2mqtt::app {

/// Who is answered, how often, and whether writes are: eip.commands, live on reload.
struct CommandPolicy {
    std::vector<core::net::Subnet> allow;  ///< resolved; empty: nobody
    bool writes = false;
    std::uint32_t max_requests_per_s = 100;
    /// Answered in full without proving their address (docs/protocol.md §9.7).
    std::vector<core::net::Subnet> trusted;
    std::uint32_t max_requests_per_s_per_source = 0;  ///< 0: no limit per source
};

/// eip.commands of `config` as a responder applies it: `allow` resolved to the subnets of
/// eip.bind's interfaces when not written (adapters::udp::local_subnets); written empty, nobody.
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
    /// `node.writes` is taken from the policy. `clock` stamps the answer of a write when its
    /// result comes; it must outlive the responder.
    CommandResponder(CommandPolicy policy, core::command::NodeInfo node, Views views, Send send,
                     WriteHandler* writes,
                     const core::Clock& clock = adapters::clock::system_clock());

    /// One datagram received on the command port.
    void on_datagram(std::span<const std::byte> datagram, const adapters::udp::Endpoint& from,
                     core::MonoTime now, core::WallTime wall);

    /// A reload's new policy; writes waiting for their result are still answered.
    void set_policy(CommandPolicy policy);

    /// The summary of refusals, drops and NAKs that stopped coming, which no next one would log
    /// (the gateway's tick).
    void flush_log(core::MonoTime now);

    const core::command::CommandCounters& counters() const { return counters_; }
    const CommandPolicy& policy() const { return policy_; }
    /// The token `address` proves itself with at `now`.
    std::uint32_t token_for_test(std::uint32_t address, core::MonoTime now) const {
        return proof_.token(address, now);
    }
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

    /// What a request's source may have: `proven` (its address proved or trusted) and the
    /// size of what it sent, which an unproven source's answers never exceed.
    struct Asker {
        adapters::udp::Endpoint from;
        bool proven = false;
        std::size_t request_size = 0;
    };

    bool within_limits(const Asker& asker, core::MonoTime now);
    void nak(std::span<const std::byte> datagram, core::command::DecodeError error,
             const Asker& asker, core::MonoTime now);
    void answer(core::command::Request request, const Asker& asker, core::MonoTime now,
                core::WallTime wall);
    void challenge(const core::command::PduHeader& request, const Asker& asker, core::MonoTime now);
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
    const core::Clock& clock_;
    core::command::AddressProof proof_;
    core::command::SourceLimiter sources_;
    core::write::RateLimiter limiter_;           ///< requesters proven or trusted
    core::write::RateLimiter unproven_limiter_;  ///< the others
    core::command::CommandCounters counters_;
    std::unordered_map<std::uint64_t, PendingWrite> pending_;
    std::uint64_t next_write_ = 1;
    /// Set while a write is handed to the WriteHandler: a result then is a refusal.
    bool staging_ = false;
    core::ThrottledLog log_;
};

}  // namespace eip2mqtt::app
