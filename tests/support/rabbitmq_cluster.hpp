#pragma once
/// A cluster of RabbitMQ 3.10 nodes (Debian 12's, with its MQTT plugin: MQTT 3.1.1 only) on
/// this machine.
///
/// Each node runs Debian's rabbitmq-server script as root with the node's own directories,
/// configuration (an MQTT listener on the loopback and no AMQP one) and enabled plugins file,
/// the cluster's epmd and cookie. The first node creates the one user every client logs in
/// as; the others join its cluster (`rabbitmqctl stop_app`, `join_cluster`, `start_app`).

#include "tests/support/broker_cluster.hpp"

namespace eip2mqtt::test {

class RabbitmqCluster : public BrokerCluster {
public:
    /// Whether RabbitMQ is installed and the tests run as root.
    static bool available();

    explicit RabbitmqCluster(int nodes = 3);

    MqttLogin login() const override { return {"eip2mqtt", "cluster", 4}; }
    /// The node's log file and what it printed.
    std::string log(int node) const override;
    /// `rabbitmqctl cluster_status` on the first running node.
    std::string members() const override;

private:
    void launch(Node& node) override;
    std::optional<std::string> join(const Node& node, const Node& first) override;
    RunResult ctl(const Node& node, std::vector<std::string> command) const;
};

}  // namespace eip2mqtt::test
