#pragma once
/// A cluster of ejabberd 23.01 nodes (Debian 12's, `mod_mqtt`: MQTT 5) on this machine.
///
/// Each node runs `ejabberdctl foreground` as the `ejabberd` user, with only an MQTT listener,
/// anonymous authentication (any user name, a non-empty password), and the cluster's epmd and
/// cookie in its own ejabberdctl.cfg.

#include "tests/support/broker_cluster.hpp"

namespace eip2mqtt::test {

class EjabberdCluster : public BrokerCluster {
public:
    /// Whether ejabberd is installed and the tests run as root, who may start nodes as the
    /// ejabberd user.
    static bool available();

    explicit EjabberdCluster(int nodes = 3);

    MqttLogin login() const override { return {"eip2mqtt", "cluster", 5}; }
    /// ejabberd.log and what the node printed.
    std::string log(int node) const override;
    /// `ejabberdctl list_cluster` on the first running node.
    std::string members() const override;

private:
    void launch(Node& node) override;
    std::optional<std::string> join(const Node& node, const Node& first) override;
    std::vector<std::string> ctl(const Node& node) const;
};

}  // namespace eip2mqtt::test
