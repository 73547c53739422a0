#pragma once
/// The parts of `sim` (sim.cpp): the values it sends, the datagrams it builds from them, the
/// production on each exchange's period, and the command port it answers, each reading the time
/// through the clock it is given.

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "eip2mqtt/adapters/udp/command_socket.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/adapters/udp/sender.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/command_port/command_responder.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/command/exchange_view.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app::detail {

/// The simulated value of a tag at `cycle`: bits toggle, integers ramp, reals follow a wave.
core::plan::Value simulated_value(const core::plan::TagSpec& tag, std::uint64_t cycle,
                                  std::size_t index);

struct SimulatedExchange {
    core::plan::ExchangePlan plan;
    std::vector<std::byte> data;
    std::vector<std::byte> datagram;
    core::wire::Header header;
    std::uint64_t cycle = 0;
    std::unique_ptr<boost::asio::steady_timer> timer;
    core::MonoTime deadline;
    std::uint64_t sent = 0;
};

/// The consumed exchanges of `config`, each with its timer on `loop`, ready to send.
std::vector<SimulatedExchange> simulated_exchanges(const core::config::Config& config,
                                                   boost::asio::io_context& loop);

/// The next datagram of `sim`: the values of its cycle, stamped `wall`; then the cycle and the
/// request id move on (65535 wraps to 0). The bytes are `sim.datagram`'s.
std::span<const std::byte> next_datagram(SimulatedExchange& sim, core::WallTime wall);

/// Sends each exchange on its period, with changing values, stamped with the clock's wall time.
class Production {
public:
    /// `sender` and `clock` must outlive the production.
    Production(adapters::udp::Sender& sender, adapters::udp::Endpoint target,
               const core::Clock& clock);

    /// Spreads the first sends over each period so exchanges do not leave in one burst: the
    /// first of `count` at the clock's now, the i-th period * i / count later. `exchanges` must
    /// outlive the production.
    void start(std::vector<SimulatedExchange>& exchanges);

private:
    void schedule(SimulatedExchange& sim);
    void send(SimulatedExchange& sim);

    adapters::udp::Sender& sender_;
    adapters::udp::Endpoint target_;
    const core::Clock& clock_;
};

/// How the simulated PLC describes `sim` on its command port: produced, active, never written,
/// configured at `started`; its image and time once it sent one.
core::command::ExchangeView sim_view(const SimulatedExchange& sim,
                                     const adapters::udp::Endpoint& target,
                                     std::span<const std::uint32_t> broadcasts,
                                     core::WallTime started);

/// The simulated PLC's command port: its socket, and the responder that describes the
/// exchanges it sends as produced ones, never written.
struct SimCommands {
    std::unique_ptr<adapters::udp::CommandSocket> socket;
    std::unique_ptr<CommandResponder> responder;
};

/// Answers the command protocol on eip.bind:`port` about `exchanges` (which must outlive it),
/// configured at the clock's wall time now.
SimCommands start_commands(boost::asio::io_context& loop, const core::config::Config& config,
                           std::uint16_t port, const std::vector<SimulatedExchange>& exchanges,
                           const adapters::udp::Endpoint& target, const core::Clock& clock);

/// The command port `options` and `config` choose; 0: none.
std::uint16_t commands_port(const SimOptions& options, const core::config::Config& config);

}  // namespace eip2mqtt::app::detail
