#include "tests/support/rabbitmq_cluster.hpp"

#include <unistd.h>

#include <filesystem>

#include "tests/support/free_port.hpp"
#include "tests/support/text_file.hpp"

namespace eip2mqtt::test {
namespace {

namespace fs = std::filesystem;

// The script itself, not /usr/sbin's wrapper, which would run the node as the rabbitmq user
// with the system's directories.
constexpr const char* kServer = "/usr/lib/rabbitmq/bin/rabbitmq-server";
constexpr const char* kCtl = "/usr/lib/rabbitmq/bin/rabbitmqctl";

}  // namespace

bool RabbitmqCluster::available() { return ::access(kServer, X_OK) == 0 && ::geteuid() == 0; }

RabbitmqCluster::RabbitmqCluster(int nodes) : BrokerCluster("rabbitmq") { form(nodes, "rabbit"); }

void RabbitmqCluster::launch(Node& node) {
    fs::create_directories(node.dir + "/log");
    fs::create_directories(node.dir + "/mnesia");
    write_text_file(node.dir + "/enabled_plugins", "[rabbitmq_mqtt].\n");
    // No AMQP listener (no port to collide with another node's); the default user is made by
    // the first node only, the others take the cluster's users when they join.
    write_text_file(node.dir + "/rabbitmq.conf",
                    "listeners.tcp = none\nmqtt.listeners.tcp.default = 127.0.0.1:" +
                        std::to_string(node.port) + "\nmqtt.allow_anonymous = false\n" +
                        "default_user = " + login().username +
                        "\ndefault_pass = " + login().password + "\nloopback_users = none\n");
    node.process = std::make_unique<ChildProcess>(
        std::vector<std::string>{kServer},
        std::map<std::string, std::string>{
            {"HOME", node.dir},
            {"ERL_EPMD_PORT", std::to_string(epmd_port())},
            {"RABBITMQ_NODENAME", node.name},
            {"RABBITMQ_DIST_PORT", std::to_string(free_tcp_port())},
            {"RABBITMQ_MNESIA_BASE", node.dir + "/mnesia"},
            {"RABBITMQ_LOG_BASE", node.dir + "/log"},
            {"RABBITMQ_ENABLED_PLUGINS_FILE", node.dir + "/enabled_plugins"},
            {"RABBITMQ_CONFIG_FILE", node.dir + "/rabbitmq"},
            {"RABBITMQ_PID_FILE", node.dir + "/pid"},
            {"RABBITMQ_SERVER_ADDITIONAL_ERL_ARGS", "-setcookie " + cookie()}});
}

RunResult RabbitmqCluster::ctl(const Node& node, std::vector<std::string> command) const {
    // rabbitmqctl is itself an Erlang node: the cluster's epmd and cookie, and the VM's HOME.
    std::vector<std::string> argv{"/usr/bin/env",
                                  "HOME=" + node.dir,
                                  "ERL_EPMD_PORT=" + std::to_string(epmd_port()),
                                  "RABBITMQ_CTL_ERL_ARGS=-setcookie " + cookie(),
                                  kCtl,
                                  "-q",
                                  "-n",
                                  node.name};
    argv.insert(argv.end(), command.begin(), command.end());
    return run_command(argv, kCommandDeadline);
}

std::optional<std::string> RabbitmqCluster::join(const Node& node, const Node& first) {
    for (const auto& step : std::vector<std::vector<std::string>>{
             {"stop_app"}, {"join_cluster", first.name}, {"start_app"}}) {
        const auto done = ctl(node, step);
        if (done.status != 0) return step.front() + ": " + done.output;
    }
    return std::nullopt;
}

std::string RabbitmqCluster::log(int node) const {
    const auto& logged = *nodes().at(node);
    return read_text_file(logged.dir + "/log/" + logged.name + ".log") +
           (logged.process ? logged.process->output() : "");
}

std::string RabbitmqCluster::members() const {
    for (const auto& node : nodes()) {
        if (node->vm > 0) return ctl(*node, {"cluster_status"}).output;
    }
    return "";
}

}  // namespace eip2mqtt::test
