// `eip2mqtt sim -c FILE`: a producer simulator. Sends every consumed exchange of a
// configuration, on its period, with values that change (ramps, toggles, waves), so that a
// gateway can be tried and tested without a PLC.

#include <spdlog/spdlog.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <vector>

#include "app/commands/detail/run_until_stopped.hpp"
#include "eip2mqtt/adapters/udp/sender.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/commands.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/encode.hpp"

namespace eip2mqtt::app {
namespace {

using core::plan::TagType;
using core::plan::Value;

/// The simulated value of a tag at `cycle`: bits toggle, integers ramp, reals follow a wave.
Value simulated_value(const core::plan::TagSpec& tag, std::uint64_t cycle, std::size_t index) {
    const std::uint64_t step = cycle + index * 7;
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
    }
    return false;
}

struct SimulatedExchange {
    core::plan::ExchangePlan plan;
    std::vector<std::byte> data;
    std::vector<std::byte> datagram;
    core::wire::Header header;
    std::uint64_t cycle = 0;
    std::unique_ptr<boost::asio::steady_timer> timer;
    std::chrono::steady_clock::time_point deadline;
};

}  // namespace

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

    boost::asio::io_context loop;
    adapters::udp::Sender sender(loop.get_executor(), {});
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
    if (exchanges.empty()) {
        spdlog::error("{} has no consumed exchange to simulate", options.config_path);
        return 1;
    }

    std::function<void(SimulatedExchange&)> send_and_schedule = [&](SimulatedExchange& sim) {
        for (std::size_t i = 0; i < sim.plan.tags.size(); ++i) {
            const auto& tag = sim.plan.tags[i].spec;
            core::plan::encode_value(sim.data, tag.type, tag.address,
                                     simulated_value(tag, sim.cycle, i));
        }
        const auto wall = std::chrono::system_clock::now().time_since_epoch();
        const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(wall).count();
        sim.header.time_s = static_cast<std::uint32_t>(ns / 1000000000);
        sim.header.time_ns = static_cast<std::uint32_t>(ns % 1000000000);
        const auto size = core::wire::encode_datagram(sim.header, sim.data, sim.datagram);
        sender.send_to(std::span(sim.datagram.data(), size), *target);
        ++sim.header.request_id;  // wraps 65535 -> 0
        ++sim.cycle;
        // docs/protocol.md §5: absolute deadlines, so the period never drifts.
        sim.deadline += sim.plan.spec.period;
        sim.timer->expires_at(sim.deadline);
        sim.timer->async_wait([&, p = &sim](const boost::system::error_code& error) {
            if (!error) send_and_schedule(*p);
        });
    };

    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < exchanges.size(); ++i) {
        auto& sim = exchanges[i];
        // Spread the first sends over the period so exchanges do not leave in one burst.
        sim.deadline = start + sim.plan.spec.period * static_cast<long>(i) /
                                   static_cast<long>(exchanges.size());
        sim.timer->expires_at(sim.deadline);
        sim.timer->async_wait([&, p = &sim](const boost::system::error_code& error) {
            if (!error) send_and_schedule(*p);
        });
        spdlog::info(
            "simulating exchange {} (producer {}, exchange {}, {} bytes, every {} ms) to {}",
            sim.plan.spec.name, core::wire::to_string(sim.plan.spec.producer_id),
            sim.plan.spec.exchange_id, sim.plan.length, sim.plan.spec.period.count(),
            adapters::udp::to_string(*target));
    }

    detail::run_until_stopped(loop, options.duration_s);
    spdlog::info("simulator sent {} datagrams ({} errors)", sender.stats().sent,
                 sender.stats().errors);
    return 0;
}

}  // namespace eip2mqtt::app
