// The command responder on UDP 7937 in the daemon (docs/protocol.md §9;
// docs/commissioning.md).

#include <spdlog/spdlog.h>

#include <chrono>
#include <string>

#include "eip2mqtt/adapters/udp/interfaces.hpp"
#include "eip2mqtt/app/gateway.hpp"

namespace eip2mqtt::app {
namespace {

std::string describe(const std::vector<core::command::Subnet>& subnets) {
    std::string text;
    for (const auto& subnet : subnets) {
        if (!text.empty()) text += ", ";
        text += core::command::to_string(subnet);
    }
    return text.empty() ? "nobody" : text;
}

}  // namespace

void Gateway::make_commands() {
    const auto& commands = config_.eip.commands;
    if (!commands.enabled) return;
    command_context_.data_port = config_.eip.port;
    command_context_.broadcasts = adapters::udp::local_broadcast_addresses();
    core::command::NodeInfo node;
    node.identification = "eip2mqtt " EIP2MQTT_VERSION;
    // The node's producer id: that of its first produced exchange, else its bind address.
    node.producer_id =
        exchanges_.producers().empty()
            ? core::wire::ProducerId{adapters::udp::parse_ipv4(config_.eip.bind).value_or(0)}
            : exchanges_.producers().front()->plan().spec.producer_id;
    command_socket_ = std::make_unique<adapters::udp::CommandSocket>(
        loop_.get_executor(), config_.eip.bind, commands.port);
    auto policy = command_policy(config_);
    spdlog::info(
        "commands: answering on UDP {}:{} to {} (trusted without proof: {}); writes {}; at most "
        "{} requests/s, {} per source",
        config_.eip.bind, command_socket_->local_port(), describe(policy.allow),
        describe(policy.trusted), policy.writes ? "on" : "off", policy.max_requests_per_s,
        policy.max_requests_per_s_per_source);
    if (policy.allow.empty() && commands.allow) {
        spdlog::warn("commands: eip.commands.allow is empty: nobody is answered");
    } else if (policy.allow.empty()) {
        spdlog::warn(
            "commands: no interface has eip.bind {}: nobody is answered until "
            "eip.commands.allow names the requesters",
            config_.eip.bind);
    }
    commands_ = std::make_unique<CommandResponder>(
        std::move(policy), std::move(node),
        [this](core::MonoTime now, core::WallTime wall) {
            return command_views(exchanges_.consumers(), exchanges_.producers(), command_context_,
                                 now, wall);
        },
        [this](std::span<const std::byte> datagram, const adapters::udp::Endpoint& to) {
            return command_socket_->send_to(datagram, to);
        },
        &writes_);
}

MetricsSources Gateway::metrics_sources(const adapters::mqtt::ClientStats& mqtt,
                                        const history::HistoryStats* history) const {
    return {exchanges_.datagram_counters(),
            writes_.counters(),
            mqtt,
            history,
            sparkplug_ ? &sparkplug_->stats() : nullptr,
            commands_ ? &commands_->counters() : nullptr,
            pair_ ? &pair_->image_counters() : nullptr,
            pair_ ? pair_->history_counters() : nullptr,
            pair_ ? &pair_->write_counters() : nullptr};
}

}  // namespace eip2mqtt::app
