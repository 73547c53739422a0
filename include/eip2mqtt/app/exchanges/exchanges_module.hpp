#pragma once
/// The exchanges as a module of the gateway: the UDP receiver, the running exchanges it routes
/// to, the writes staged on them (WriteDispatcher), and the fan-out every northbound module
/// joins to hear what they report. A datagram goes receiver -> Exchanges::route -> consumer ->
/// FanOut; a write goes a northbound -> WriteDispatcher -> Exchanges::stage -> producer.
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/udp/receiver.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app {

class ExchangesModule final : public Module {
public:
    /// Binds the receiver's port and joins its groups; throws std::exception when it cannot.
    /// `options` are the role's (redundancy::Role::exchanges_options); the socket's are
    /// completed from `config`. No exchange runs before apply_plans().
    ExchangesModule(const core::config::Config& config, boost::asio::any_io_executor loop,
                    const core::Clock& clock, ExchangesOptions options);

    /// What the exchanges report to: a northbound module adds itself.
    northbound::FanOut& north() { return north_; }
    WriteDispatcher& writes() { return writes_; }
    Exchanges& exchanges() { return exchanges_; }
    const Exchanges& exchanges() const { return exchanges_; }
    std::uint16_t local_port() const { return receiver_.local_port(); }

    /// Runs the exchanges of `plans` (Exchanges::apply), counts the writes it cancelled, and
    /// returns the line that logs it. Throws as Exchanges::apply does.
    std::string apply_plans(std::vector<core::plan::ExchangePlan> plans);

    void start(core::MonoTime now) override;
    /// What arrived in time is read before any exchange is judged stale.
    void tick(const TickTimes& times) override;
    /// The receiver first; then the last saves reach the disk, and their write results the
    /// northbounds' queues before those stop.
    void stop() override;
    /// The multicast groups of `next`; false, with the groups kept, when they cannot be joined.
    bool prepare(const core::config::Config& next) override;

private:
    const core::Clock& clock_;
    std::vector<core::config::MulticastGroup> multicast_;
    northbound::FanOut north_;
    WriteDispatcher writes_;
    Exchanges exchanges_;
    adapters::udp::Receiver receiver_;
};

}  // namespace eip2mqtt::app
