// `eip2mqtt sim -c FILE`: a producer simulator. Sends every consumed exchange of a
// configuration, on its period, with values that change (ramps, toggles, waves), so that a
// gateway can be tried and tested without a PLC; and answers the command protocol on UDP 7937
// about them (docs/protocol.md §9), so that `discover` and the responder can be too.

#include <spdlog/spdlog.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <optional>
#include <vector>

#include "app/cli/detail/run_until_stopped.hpp"
#include "app/cli/detail/simulator.hpp"
#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/udp/interfaces.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/command_port/command_views.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/plan/scaling.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/encode.hpp"

namespace eip2mqtt::app {
namespace detail {

using core::plan::TagType;
using core::plan::Value;

/// A scaled tag's raw value for an engineering value sweeping most of its span, so that the
/// demo shows units; nullopt for a scale without a span (gain and offset).
std::optional<Value> simulated_scaled(const core::plan::TagSpec& tag, std::uint64_t step) {
    const auto span = tag.scale() ? core::plan::eu_span(*tag.scale()) : std::nullopt;
    if (!span) return std::nullopt;
    const double eu = span->lo + (span->hi - span->lo) *
                                     (0.5 + 0.45 * std::sin(static_cast<double>(step) / 20.0));
    auto raw = core::plan::to_raw(eu, *tag.scale(), tag.type);
    return raw ? std::optional(std::move(raw).value()) : std::nullopt;
}

Value simulated_scalar(const core::plan::TagSpec& tag, std::uint64_t step) {
    if (auto scaled = simulated_scaled(tag, step)) return *scaled;
    switch (tag.type) {
        case TagType::bit:
            return (step / 10 + tag.address.bit) % 2 == 0;
        case TagType::byte:
            return static_cast<std::uint64_t>(step % 256);
        case TagType::int_:
            return static_cast<std::int64_t>(step % 2000) - 1000;
        case TagType::word:
            return static_cast<std::uint64_t>(step % 65536);
        case TagType::dint:
            return static_cast<std::int64_t>(step * 1000 % 200000) - 100000;
        case TagType::udint:
            return static_cast<std::uint64_t>(step * 100000);
        case TagType::real:
            return static_cast<float>(std::round(1000.0 * (100.0 + 50.0 * std::sin(step / 20.0))) /
                                      1000.0);
        case TagType::lint:
            return static_cast<std::int64_t>(step) * 1000000 - 500000000;
        case TagType::lreal:
            return 1000.0 + 0.5 * static_cast<double>(step);
        case TagType::string: {
            // A batch number that moves on every 50 cycles, cut to the field.
            auto text = "BATCH-" + std::to_string(1000 + step / 50);
            text.resize(std::min<std::size_t>(text.size(), tag.count));
            return core::plan::make_text(std::move(text));
        }
    }
    return false;
}

Value simulated_value(const core::plan::TagSpec& tag, std::uint64_t cycle, std::size_t index) {
    const std::uint64_t step = cycle + index * 7;
    if (!tag.is_array()) return simulated_scalar(tag, step);
    // Each element its own phase, so that an array's elements differ.
    std::vector<Value> items;
    items.reserve(tag.count);
    for (std::size_t i = 0; i < tag.count; ++i)
        items.push_back(simulated_scalar(tag, step + i * 3));
    return core::plan::make_list(std::move(items));
}

core::command::ExchangeView sim_view(const SimulatedExchange& sim,
                                     const adapters::udp::Endpoint& target,
                                     std::span<const std::uint32_t> broadcasts,
                                     core::WallTime started) {
    core::command::ExchangeView view;
    view.plan = &sim.plan;
    view.mode = core::command::ExchangeMode::produced;
    view.state = core::command::ExchangeState::active;
    view.destination = target.address;
    view.destination_type = destination_type(target.address, broadcasts);
    view.port = target.port;
    view.config_time_s = static_cast<std::uint32_t>(
        std::chrono::duration_cast<std::chrono::seconds>(started.time_since_epoch()).count());
    view.messages = core::command::wrap32(sim.sent);
    if (sim.sent > 0) {
        view.image = sim.data;
        view.time_s = sim.header.time_s;
        view.time_ns = sim.header.time_ns;
    }
    return view;
}

SimCommands start_commands(boost::asio::io_context& loop, const core::config::Config& config,
                           std::uint16_t port, const std::vector<SimulatedExchange>& exchanges,
                           const adapters::udp::Endpoint& target, const core::Clock& clock) {
    SimCommands commands;
    commands.socket =
        std::make_unique<adapters::udp::CommandSocket>(loop.get_executor(), config.eip.bind, port);
    core::command::NodeInfo node;
    node.producer_id = exchanges.front().plan.spec.producer_id;
    node.identification = "eip2mqtt sim " EIP2MQTT_VERSION;
    const auto started = clock.wall();
    auto* socket = commands.socket.get();
    commands.responder = std::make_unique<CommandResponder>(
        command_policy(config), node,
        [&exchanges, target, started, broadcasts = adapters::udp::local_broadcast_addresses()](
            core::MonoTime, core::WallTime) {
            std::vector<core::command::ExchangeView> views;
            for (const auto& sim : exchanges)
                views.push_back(sim_view(sim, target, broadcasts, started));
            return views;
        },
        [socket](std::span<const std::byte> bytes, const adapters::udp::Endpoint& to) {
            return socket->send_to(bytes, to);
        },
        nullptr, clock);
    auto* responder = commands.responder.get();
    commands.socket->start(
        [responder, &clock](std::span<const std::byte> bytes, const adapters::udp::Endpoint& from) {
            responder->on_datagram(bytes, from, clock.monotonic(), clock.wall());
        });
    spdlog::info("answering the command protocol on UDP {}:{}", config.eip.bind,
                 commands.socket->local_port());
    return commands;
}

std::uint16_t commands_port(const SimOptions& options, const core::config::Config& config) {
    if (options.commands_port >= 0) return static_cast<std::uint16_t>(options.commands_port);
    return config.eip.commands.enabled ? config.eip.commands.port : 0;
}

std::vector<SimulatedExchange> simulated_exchanges(const core::config::Config& config,
                                                   boost::asio::io_context& loop) {
    std::vector<SimulatedExchange> exchanges;
    for (auto& plan : core::config::make_plans(config)) {
        if (plan.spec.direction != core::plan::Direction::consume) continue;
        SimulatedExchange sim;
        sim.plan = std::move(plan);
        sim.data.assign(sim.plan.length, std::byte{0});
        sim.datagram.resize(core::wire::header_size + sim.plan.length);
        sim.header.producer_id = sim.plan.spec.producer_id;
        sim.header.exchange_id = sim.plan.spec.exchange_id;
        sim.header.signature = sim.plan.spec.signature.to_wire();
        sim.timer = std::make_unique<boost::asio::steady_timer>(loop);
        exchanges.push_back(std::move(sim));
    }
    return exchanges;
}

std::span<const std::byte> next_datagram(SimulatedExchange& sim, core::WallTime wall) {
    for (std::size_t i = 0; i < sim.plan.tags.size(); ++i) {
        const auto& tag = sim.plan.tags[i].spec;
        core::plan::encode_tag(sim.data, tag, simulated_value(tag, sim.cycle, i));
    }
    const auto ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(wall.time_since_epoch()).count();
    sim.header.time_s = static_cast<std::uint32_t>(ns / 1000000000);
    sim.header.time_ns = static_cast<std::uint32_t>(ns % 1000000000);
    const auto size = core::wire::encode_datagram(sim.header, sim.data, sim.datagram);
    ++sim.header.request_id;  // wraps 65535 -> 0
    ++sim.cycle;
    return std::span(sim.datagram.data(), size);
}

Production::Production(adapters::udp::Sender& sender, adapters::udp::Endpoint target,
                       const core::Clock& clock)
    : sender_(sender), target_(target), clock_(clock) {}

void Production::start(std::vector<SimulatedExchange>& exchanges) {
    const auto start = clock_.monotonic();
    for (std::size_t i = 0; i < exchanges.size(); ++i) {
        auto& sim = exchanges[i];
        sim.deadline = start + sim.plan.spec.period * static_cast<long>(i) /
                                   static_cast<long>(exchanges.size());
        schedule(sim);
        spdlog::info(
            "simulating exchange {} (producer {}, exchange {}, {} bytes, every {} ms) to {}",
            sim.plan.spec.name, core::wire::to_string(sim.plan.spec.producer_id),
            sim.plan.spec.exchange_id, sim.plan.length, sim.plan.spec.period.count(),
            adapters::udp::to_string(target_));
    }
}

void Production::schedule(SimulatedExchange& sim) {
    sim.timer->expires_at(sim.deadline);
    sim.timer->async_wait([this, p = &sim](const boost::system::error_code& error) {
        if (!error) send(*p);
    });
}

void Production::send(SimulatedExchange& sim) {
    if (sender_.send_to(next_datagram(sim, clock_.wall()), target_)) ++sim.sent;
    // docs/protocol.md §5: absolute deadlines, so the period never drifts.
    sim.deadline += sim.plan.spec.period;
    schedule(sim);
}

}  // namespace detail

int run_sim(const SimOptions& options) {
    setup_logging(options.log_level);
    auto loaded = adapters::yaml::load_config(options.config_path);
    if (!loaded) {
        for (const auto& diagnostic : loaded.error()) spdlog::error("{}", diagnostic.to_string());
        return 1;
    }
    const auto& config = loaded.value();
    const auto port =
        options.port != 0 ? static_cast<std::uint16_t>(options.port) : config.eip.port;
    const auto target = adapters::udp::resolve_endpoint(options.target, port);
    if (!target) {
        spdlog::error("cannot resolve target {}", options.target);
        return 1;
    }

    const auto& clock = adapters::clock::system_clock();
    boost::asio::io_context loop;
    adapters::udp::Sender sender(loop.get_executor(), {});
    auto exchanges = detail::simulated_exchanges(config, loop);
    if (exchanges.empty()) {
        spdlog::error("{} has no consumed exchange to simulate", options.config_path);
        return 1;
    }
    detail::Production production(sender, *target, clock);
    production.start(exchanges);
    detail::SimCommands commands;
    if (const auto commands_at = detail::commands_port(options, config); commands_at != 0) {
        commands = detail::start_commands(loop, config, commands_at, exchanges, *target, clock);
    }

    detail::run_until_stopped(loop, options.duration_s);
    if (commands.socket) commands.socket->stop();
    spdlog::info("simulator sent {} datagrams ({} errors)", sender.stats().sent,
                 sender.stats().errors);
    return 0;
}

}  // namespace eip2mqtt::app
