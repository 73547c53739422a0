// The command protocol's responder (docs/protocol.md §9): allow list, rate limit, NAKs,
// answers, and writes answered after their datagram.

#include "eip2mqtt/app/command_port/command_responder.hpp"

#include <spdlog/spdlog.h>

#include <charconv>
#include <chrono>
#include <random>

#include "eip2mqtt/adapters/udp/interfaces.hpp"
#include "eip2mqtt/core/command/command_nak.hpp"
#include "eip2mqtt/core/command/encode.hpp"

namespace eip2mqtt::app {
namespace {

using core::command::CommandStatus;

std::optional<std::uint64_t> id_of(std::string_view text) {
    std::uint64_t id = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
    if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
    return id;
}

// The proof's secret, new at every start: tokens are not meant to outlive the process.
core::command::ProofKey random_key() {
    std::random_device random;
    const auto word = [&] { return std::uint64_t{random()} << 32 | random(); };
    return {word(), word()};
}

}  // namespace

CommandPolicy command_policy(const core::config::Config& config) {
    const auto& commands = config.eip.commands;
    CommandPolicy policy{commands.allow.value_or(std::vector<core::net::Subnet>{}), commands.writes,
                         commands.max_requests_per_s, commands.trusted,
                         commands.max_requests_per_s_per_source};
    if (!commands.allow) {
        policy.allow =
            adapters::udp::local_subnets(adapters::udp::parse_ipv4(config.eip.bind).value_or(0));
    }
    return policy;
}

CommandResponder::CommandResponder(CommandPolicy policy, core::command::NodeInfo node, Views views,
                                   Send send, WriteHandler* writes, const core::Clock& clock)
    : policy_(std::move(policy)),
      node_(std::move(node)),
      views_(std::move(views)),
      send_(std::move(send)),
      writes_(writes),
      clock_(clock),
      proof_(random_key()),
      sources_(policy_.max_requests_per_s_per_source),
      limiter_(policy_.max_requests_per_s),
      unproven_limiter_(policy_.max_requests_per_s) {
    node_.writes = policy_.writes && writes_ != nullptr;
}

void CommandResponder::set_policy(CommandPolicy policy) {
    if (policy.max_requests_per_s != policy_.max_requests_per_s) {
        limiter_ = core::write::RateLimiter(policy.max_requests_per_s);
        unproven_limiter_ = core::write::RateLimiter(policy.max_requests_per_s);
    }
    if (policy.max_requests_per_s_per_source != policy_.max_requests_per_s_per_source) {
        sources_ = core::command::SourceLimiter(policy.max_requests_per_s_per_source);
    }
    policy_ = std::move(policy);
    node_.writes = policy_.writes && writes_ != nullptr;
}

void CommandResponder::on_datagram(std::span<const std::byte> datagram,
                                   const adapters::udp::Endpoint& from, core::MonoTime now,
                                   core::WallTime wall) {
    // Who may ask comes first, then how often: a source outside `allow` spends no token.
    if (!core::net::allowed(policy_.allow, from.address)) {
        ++counters_.refused;
        return log("refused a command datagram from a source outside eip.commands.allow", from,
                   now);
    }
    const Asker asker{from,
                      core::net::allowed(policy_.trusted, from.address) ||
                          proof_.proves(datagram, from.address, now),
                      datagram.size()};
    if (!within_limits(asker, now)) return;
    auto request = core::command::decode_request(datagram);
    if (!request) return nak(datagram, request.error(), asker, now);
    answer(std::move(request).value(), asker, now, wall);
}

bool CommandResponder::within_limits(const Asker& asker, core::MonoTime now) {
    if (!sources_.allow(asker.from.address, now)) {
        ++counters_.dropped;
        ++counters_.dropped_per_source;
        log("dropped a command datagram over eip.commands.max_requests_per_s_per_source",
            asker.from, now);
        return false;
    }
    // Sources that cannot prove their address have a budget of their own: forged ones cannot
    // spend that of the requesters that can.
    if (!(asker.proven ? limiter_ : unproven_limiter_).allow(now)) {
        ++counters_.dropped;
        log("dropped a command datagram over eip.commands.max_requests_per_s", asker.from, now);
        return false;
    }
    return true;
}

void CommandResponder::nak(std::span<const std::byte> datagram, core::command::DecodeError error,
                           const Asker& asker, core::MonoTime now) {
    const auto nak = core::command::make_nak(datagram, error);
    const auto bytes =
        nak ? core::command::encode(nak->header, nak->nak) : std::vector<std::byte>{};
    // A NAK larger than its request goes only to a requester that proved its address.
    if (!nak || (!asker.proven && bytes.size() > asker.request_size)) {
        ++counters_.ignored;
        return;
    }
    ++counters_.naks[static_cast<std::size_t>(error)];
    reply(bytes, asker.from);
    log("answered a command request with a NAK (" + std::string(core::command::to_string(error)) +
            ")",
        asker.from, now);
}

void CommandResponder::answer(core::command::Request request, const Asker& asker,
                              core::MonoTime now, core::WallTime wall) {
    const auto type = request.header.type;
    const bool writing = type == core::command::PduType::write_request ||
                         type == core::command::PduType::masked_write_request;
    // A write from a source that may be forged is not taken (§9.7).
    if (writing && !asker.proven) return challenge(request.header, asker, now);
    const auto views = views_(now, wall);
    auto answered = core::command::answer(request, node_, views);
    auto& answered_count = counters_.requests[core::command::request_index(type)];
    if (auto* staged = std::get_if<core::command::StageWrites>(&answered)) {
        ++answered_count;
        return stage(std::move(request), std::move(*staged), asker.from);
    }
    const auto& response = std::get<std::vector<std::byte>>(answered);
    if (!asker.proven && response.size() > asker.request_size) {
        return challenge(request.header, asker, now);
    }
    ++answered_count;
    if (std::to_integer<std::uint8_t>(response[5]) != 0) ++counters_.errors;
    reply(response, asker.from);
}

void CommandResponder::challenge(const core::command::PduHeader& request, const Asker& asker,
                                 core::MonoTime now) {
    ++counters_.challenged;
    reply(core::command::challenge(request, asker.request_size,
                                   proof_.token(asker.from.address, now)),
          asker.from);
}

void CommandResponder::stage(core::command::Request request, core::command::StageWrites writes,
                             const adapters::udp::Endpoint& from) {
    if (pending_.size() >= max_pending) {
        ++counters_.errors;
        return reply(core::command::write_response(request, CommandStatus::rejected), from);
    }
    const auto id = next_write_++;
    WriteRequest write;
    write.reply.origin = this;
    write.reply.via = WriteOrigin::commands;
    write.reply.correlation_data = std::to_string(id);
    write.target = "UDP " + adapters::udp::to_string(from);
    // A value the write checks refused goes the same way, to be counted by its reason.
    if (writes.rejection) {
        write.outcome = std::move(*writes.rejection);
    } else {
        write.outcome = ExchangeWrite{writes.exchange, std::move(writes.writes)};
    }
    pending_.emplace(id, PendingWrite{std::move(request), from});
    staging_ = true;
    writes_->on_write(std::move(write));
    staging_ = false;
}

void CommandResponder::write_result(const WriteReply& reply_to,
                                    std::optional<std::string_view> error) {
    const auto id = id_of(reply_to.correlation_data);
    const auto found = id ? pending_.find(*id) : pending_.end();
    if (found == pending_.end()) return;
    // A refusal while the write is being handed over is the write checks' (rate limit, full
    // queue); one later is the datagram's or the save's.
    const auto status = !error     ? CommandStatus::success
                        : staging_ ? CommandStatus::rejected
                                   : CommandStatus::failed;
    if (status != CommandStatus::success) ++counters_.errors;
    const auto wall = clock_.wall();
    reply(
        core::command::write_response(found->second.request, status, core::wire_time(wall).seconds,
                                      core::wire_time(wall).nanoseconds),
        found->second.to);
    pending_.erase(found);
}

void CommandResponder::reply(std::span<const std::byte> response,
                             const adapters::udp::Endpoint& to) {
    // A response the kernel refuses is not retried: the requester asks again.
    send_(response, to);
}

void CommandResponder::log(std::string_view what, const adapters::udp::Endpoint& from,
                           core::MonoTime now) {
    const auto count = log_.record(now);
    if (count == 1) {
        spdlog::warn("commands: {} ({}); such events are summarised at most once a minute", what,
                     adapters::udp::to_string(from));
    } else if (count > 1) {
        log_summary(count);
    }
}

void CommandResponder::flush_log(core::MonoTime now) {
    if (const auto count = log_.flush(now)) log_summary(count);
}

void CommandResponder::log_summary(std::uint64_t count) const {
    std::uint64_t naks = 0;
    for (const auto n : counters_.naks) naks += n;
    spdlog::warn(
        "commands: {} datagrams refused, dropped or NAKed in the last {} s; {} refused, "
        "{} dropped, {} NAKs so far",
        count, log_.interval().count(), counters_.refused, counters_.dropped, naks);
}

}  // namespace eip2mqtt::app
