#pragma once
/// The command port (UDP 7937, docs/protocol.md §9) as a module of the gateway: its socket, the
/// responder that answers on it from the running exchanges, and the responder's policy, live
/// on reload. Made only with `eip.commands.enabled` (make_command_port).
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <memory>

#include "eip2mqtt/adapters/udp/command_socket.hpp"
#include "eip2mqtt/app/command_port/command_responder.hpp"
#include "eip2mqtt/app/command_port/command_views.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app::command_port {

class CommandPort final : public Module {
public:
    /// Binds the port; throws std::exception when it cannot. `exchanges` are answered from and
    /// `writes` takes the writes; both outlive the port.
    CommandPort(const core::config::Config& config, boost::asio::any_io_executor loop,
                const Exchanges& exchanges, WriteHandler& writes, const core::Clock& clock);

    void start(core::MonoTime now) override;
    void tick(const TickTimes& times) override;
    void stop() override;
    void apply(const core::config::Config& next) override;
    void add_metrics(MetricsSources& sources) override;

private:
    const Exchanges& exchanges_;
    const core::Clock& clock_;
    CommandViewContext context_;
    adapters::udp::CommandSocket socket_;
    CommandResponder responder_;
};

/// The command port of `config`; null unless `eip.commands.enabled`.
std::unique_ptr<Module> make_command_port(const core::config::Config& config,
                                          boost::asio::any_io_executor loop,
                                          const Exchanges& exchanges, WriteHandler& writes,
                                          const core::Clock& clock);

}  // namespace eip2mqtt::app::command_port
