#pragma once
/// A real ejabberd cluster (Debian's 23.01, `mod_mqtt`) of nodes on this machine, started,
/// joined and stopped by the test, like Mosquitto.
///
/// Each node has its own directory (configuration, spool, logs), its own MQTT port on the
/// loopback and a name of its own (`eip2mqtt<pid>n<i>@localhost`); the nodes find each other
/// through an epmd the cluster starts on a free port, so nothing outlives the test, share a
/// cookie of the cluster's own, and run as the `ejabberd` user. MQTT clients log in with `login()`
/// (anonymous authentication: any name, a non-empty password).

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::test {

class EjabberdCluster {
public:
    /// Whether ejabberd is installed (tools/install-deps.sh installs it) and the tests run as
    /// root, who may start nodes as the ejabberd user.
    static bool available();

    /// Starts `nodes` nodes and joins them into one cluster; returns once every node accepts
    /// MQTT connections and the first lists them all, or fails the test (ADD_FAILURE) and
    /// leaves ready() false.
    explicit EjabberdCluster(int nodes = 3);
    /// Kills every node still running, and the cluster's epmd.
    ~EjabberdCluster();
    EjabberdCluster(const EjabberdCluster&) = delete;
    EjabberdCluster& operator=(const EjabberdCluster&) = delete;

    bool ready() const { return ready_; }
    int size() const { return static_cast<int>(nodes_.size()); }
    std::uint16_t port(int node) const;
    std::string url(int node) const;  ///< tcp://127.0.0.1:PORT
    /// Every node's URL as a YAML flow list for `mqtt.url`, from node `first` on, round.
    std::string url_list(int first = 0) const;
    static MqttLogin login() { return {"eip2mqtt", "cluster"}; }

    /// SIGKILL of the node's Erlang VM, as a crash would; returns once its port is closed.
    void kill(int node);
    /// The node's log (ejabberd.log and what it printed).
    std::string log(int node) const;
    /// What the first running node says of the cluster (`ejabberdctl list_cluster`).
    std::string members() const;

private:
    struct Node;
    void start_node(Node& node);
    std::vector<std::string> ctl(const Node& node) const;

    std::string dir_;
    std::uint16_t epmd_port_ = 0;
    std::unique_ptr<ChildProcess> epmd_;
    std::vector<std::unique_ptr<Node>> nodes_;
    bool ready_ = false;
};

}  // namespace eip2mqtt::test
