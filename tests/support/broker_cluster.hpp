#pragma once
/// A real broker cluster of nodes on this machine, started, joined and stopped by the test,
/// like Mosquitto: ejabberd 23.01 (`mod_mqtt`, MQTT 5) or RabbitMQ 3.10 (its MQTT plugin,
/// MQTT 3.1.1 only), both Debian 12's, both Erlang.
///
/// Each node has its own directory (configuration, database, logs), its own MQTT port on the
/// loopback and a name of its own; the nodes find each other through an epmd the cluster starts
/// on a free port, so nothing outlives the test and two tests' clusters never meet, and share a
/// cookie of the cluster's own. Clients log in with login().

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::test {

class BrokerCluster {
public:
    enum class Kind { ejabberd, rabbitmq };
    static std::string name(Kind kind);
    /// Whether the broker is installed (tools/install-deps.sh installs both) and the tests run
    /// as root, who may start the nodes (ejabberd's as its own user).
    static bool available(Kind kind);
    /// Starts `nodes` nodes of `kind` and joins them into one cluster; nullptr where the broker
    /// is not available(). Check ready() before use.
    static std::unique_ptr<BrokerCluster> start(Kind kind, int nodes = 3);

    /// Kills every node still running, and the cluster's epmd.
    virtual ~BrokerCluster();
    BrokerCluster(const BrokerCluster&) = delete;
    BrokerCluster& operator=(const BrokerCluster&) = delete;

    /// Every node accepts MQTT connections and the first lists them all as members; otherwise
    /// the test was failed (ADD_FAILURE) saying why.
    bool ready() const { return ready_; }
    int size() const { return static_cast<int>(nodes_.size()); }
    std::uint16_t port(int node) const;
    std::string url(int node) const;  ///< tcp://127.0.0.1:PORT
    /// Every node's URL as a YAML flow list for `mqtt.url`, from node `first` on, round.
    std::string url_list(int first = 0) const;
    /// What an MQTT client gives every node: a user name, a password, the protocol version.
    virtual MqttLogin login() const = 0;
    /// The gateway's `mqtt` keys for login(), but the password (a credential): indented lines.
    std::string mqtt_keys() const;

    /// SIGKILL of the node's Erlang VM, as a crash would; returns once its port is closed.
    void kill(int node);
    /// The node's log files and what it printed.
    virtual std::string log(int node) const = 0;
    /// What the first running node says of the cluster's members.
    virtual std::string members() const = 0;

protected:
    struct Node {
        std::string name;  ///< the Erlang node name, NAME@localhost
        std::string dir;
        std::uint16_t port = 0;  ///< MQTT
        std::unique_ptr<ChildProcess> process;
        pid_t vm = -1;  ///< the Erlang VM, from the pid file the node writes in its directory
    };
    static constexpr auto kCommandDeadline = std::chrono::seconds(90);

    /// A directory of the cluster's own under /tmp, named after `broker`, and its epmd.
    explicit BrokerCluster(const std::string& broker);
    /// Called at the end of the derived class's constructor: launches every node at once, waits
    /// until each accepts MQTT connections, joins the others to the first, checks the members.
    void form(int nodes, const std::string& name_prefix);
    /// Writes the node's files and starts it (node.process), without waiting.
    virtual void launch(Node& node) = 0;
    /// Joins `node` to the cluster of `first`; the command's output when that failed.
    virtual std::optional<std::string> join(const Node& node, const Node& first) = 0;

    const std::string& dir() const { return dir_; }
    std::uint16_t epmd_port() const { return epmd_port_; }
    std::string cookie() const;
    const std::vector<std::unique_ptr<Node>>& nodes() const { return nodes_; }

private:
    bool wait_started(int index);

    std::string dir_;
    std::uint16_t epmd_port_ = 0;
    std::unique_ptr<ChildProcess> epmd_;
    std::vector<std::unique_ptr<Node>> nodes_;
    bool ready_ = false;
};

}  // namespace eip2mqtt::test
