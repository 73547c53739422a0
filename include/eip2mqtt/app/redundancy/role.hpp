#pragma once
/// This unit's role as a module of the gateway (docs/redundancy.md): a hot-standby pair's
/// (redundancy::Pair, made with `redundancy:`) or a single unit's, which always leads and fences
/// nothing. The parts it gates ask it while they are built (what their connections may send,
/// the exchanges' options, the publisher of a session only the role's holder keeps), so that
/// no part asks whether there is a pair; wire() then hands it the parts it keeps in step.
///
/// Threading: the loop, but for the functions may_send() returns (the sender threads).

#include <boost/asio/any_io_executor.hpp>
#include <functional>
#include <memory>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app {
class WriteDispatcher;
}
namespace eip2mqtt::app::northbound {
class FanOut;
struct Northbounds;
}  // namespace eip2mqtt::app::northbound

namespace eip2mqtt::app::redundancy {

/// What the role keeps in step, borrowed: each outlives the role's use of it (until stop()).
struct RoleParts {
    const core::config::Config& config;
    northbound::Northbounds& northbounds;
    WriteDispatcher& writes;
    Exchanges& exchanges;
    northbound::FanOut& north;
};

class Role : public Module {
public:
    using MaySend = std::function<bool(const adapters::mqtt::Message&)>;

    /// ClientOptions::may_send of a connection whose publications in `fenced` (every one when
    /// null) go only while this unit holds the role; null when nothing is fenced.
    virtual MaySend may_send(MaySend fenced) = 0;
    /// The exchanges' options the role sets (its gate of production, images, request ids).
    virtual ExchangesOptions exchanges_options() = 0;
    /// Between a session's connection and its publisher (the Sparkplug node's): nothing
    /// passes unless this unit holds the role; null when the session is always this unit's.
    virtual std::unique_ptr<adapters::mqtt::Publisher> session_gate(
        adapters::mqtt::Publisher& inner) = 0;
    /// Whether sessions open when the role is taken (and end when it is given up) rather than
    /// when the gateway starts.
    virtual bool sessions_follow_role() const = 0;
    /// Hands it the parts it keeps in step, once they are all built.
    virtual void wire(RoleParts parts) = 0;
};

/// The role `config` gives this unit: the pair's with `redundancy:`, else a single unit's.
std::unique_ptr<Role> make_role(const core::config::Config& config,
                                boost::asio::any_io_executor loop, const core::Clock& clock);

}  // namespace eip2mqtt::app::redundancy
