// The command responder on UDP 7937 in the daemon (docs/protocol.md §9;
// docs/commissioning.md).

#include "eip2mqtt/app/command_port/command_port.hpp"

#include <spdlog/spdlog.h>

#include <string>

#include "eip2mqtt/adapters/udp/interfaces.hpp"
#include "eip2mqtt/app/health/metrics.hpp"

namespace eip2mqtt::app::command_port {
namespace {

std::string describe(const std::vector<core::net::Subnet>& subnets) {
    std::string text;
    for (const auto& subnet : subnets) {
        if (!text.empty()) text += ", ";
        text += core::net::to_string(subnet);
    }
    return text.empty() ? "nobody" : text;
}

/// The node: its producer id is that of its first produced exchange, else its bind address.
core::command::NodeInfo node_info(const core::config::Config& config, const Exchanges& exchanges) {
    core::command::NodeInfo node;
    node.identification = "eip2mqtt " EIP2MQTT_VERSION;
    node.producer_id =
        exchanges.producers().empty()
            ? core::wire::ProducerId{adapters::udp::parse_ipv4(config.eip.bind).value_or(0)}
            : exchanges.producers().front()->plan().spec.producer_id;
    return node;
}

void log_policy(const core::config::Config& config, const CommandPolicy& policy,
                std::uint16_t port) {
    spdlog::info(
        "commands: answering on UDP {}:{} to {} (trusted without proof: {}); writes {}; at most "
        "{} requests/s, {} per source",
        config.eip.bind, port, describe(policy.allow), describe(policy.trusted),
        policy.writes ? "on" : "off", policy.max_requests_per_s,
        policy.max_requests_per_s_per_source);
    if (policy.allow.empty() && config.eip.commands.allow) {
        spdlog::warn("commands: eip.commands.allow is empty: nobody is answered");
    } else if (policy.allow.empty()) {
        spdlog::warn(
            "commands: no interface has eip.bind {}: nobody is answered until "
            "eip.commands.allow names the requesters",
            config.eip.bind);
    }
}

}  // namespace

CommandPort::CommandPort(const core::config::Config& config, boost::asio::any_io_executor loop,
                         const Exchanges& exchanges, WriteHandler& writes, const core::Clock& clock)
    : exchanges_(exchanges),
      clock_(clock),
      context_{config.eip.port, adapters::udp::local_broadcast_addresses()},
      socket_(std::move(loop), config.eip.bind, config.eip.commands.port),
      responder_(
          command_policy(config), node_info(config, exchanges),
          [this](core::MonoTime now, core::WallTime wall) {
              return command_views(exchanges_.consumers(), exchanges_.producers(), context_, now,
                                   wall);
          },
          [this](std::span<const std::byte> datagram, const adapters::udp::Endpoint& to) {
              return socket_.send_to(datagram, to);
          },
          &writes, clock_) {
    log_policy(config, responder_.policy(), socket_.local_port());
}

void CommandPort::start(core::MonoTime /*now*/) {
    socket_.start([this](std::span<const std::byte> bytes, const adapters::udp::Endpoint& from) {
        responder_.on_datagram(bytes, from, clock_.monotonic(), clock_.wall());
    });
}

void CommandPort::tick(const TickTimes& times) { responder_.flush_log(times.now); }

void CommandPort::stop() { socket_.stop(); }

void CommandPort::apply(const core::config::Config& next) {
    responder_.set_policy(command_policy(next));
}

void CommandPort::add_metrics(MetricsSources& sources) {
    sources.commands = &responder_.counters();
}

std::unique_ptr<Module> make_command_port(const core::config::Config& config,
                                          boost::asio::any_io_executor loop,
                                          const Exchanges& exchanges, WriteHandler& writes,
                                          const core::Clock& clock) {
    if (!config.eip.commands.enabled) return nullptr;
    return std::make_unique<CommandPort>(config, std::move(loop), exchanges, writes, clock);
}

}  // namespace eip2mqtt::app::command_port
