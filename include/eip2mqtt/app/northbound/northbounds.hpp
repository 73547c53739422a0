#pragma once
/// The northbound modules a configuration makes, in dependency order: for each MQTT connection
/// (one, or each of a list), its JSON topic tree (always: it carries the gateway's own topics)
/// and its store and forward with its `store_and_forward`; then the Sparkplug B edge node with
/// `sparkplug:`, on the connection `sparkplug.connection` names. Each joins the
/// exchanges' fan-out (the JSON tree unless `sparkplug.uns: false`) and hands its writes to the
/// WriteDispatcher. The next protocol is one more module made here.

#include <boost/asio/any_io_executor.hpp>
#include <memory>
#include <vector>

#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app {
class Exchanges;
class WriteDispatcher;
}  // namespace eip2mqtt::app
namespace eip2mqtt::app::redundancy {
class Role;
}
namespace eip2mqtt::app::northbound::json_tree {
class JsonTreeModule;
}
namespace eip2mqtt::app::northbound::sparkplug {
class SparkplugModule;
}

namespace eip2mqtt::app::northbound {

class FanOut;

/// What the northbound modules are built from, borrowed: each outlives them.
struct NorthboundParts {
    boost::asio::any_io_executor loop;
    const core::Clock& clock;
    redundancy::Role& role;
    WriteDispatcher& writes;
    Exchanges& exchanges;
    FanOut& north;
};

struct Northbounds {
    /// Owned, in dependency order: started in it, stopped in reverse.
    std::vector<std::unique_ptr<Module>> modules;
    json_tree::JsonTreeModule* tree = nullptr;  ///< always: the first connection's
    /// Every MQTT connection's tree, the first first (`mqtt` as a list).
    std::vector<json_tree::JsonTreeModule*> trees;
    sparkplug::SparkplugModule* node = nullptr;  ///< with `sparkplug:`
};

/// Throws std::exception when a module cannot be made (an unreadable password file).
Northbounds make_northbounds(const core::config::Config& config, const NorthboundParts& parts);

}  // namespace eip2mqtt::app::northbound
