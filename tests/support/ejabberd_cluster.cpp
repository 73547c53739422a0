#include "tests/support/ejabberd_cluster.hpp"

#include <pwd.h>
#include <unistd.h>

#include <filesystem>

#include "tests/support/text_file.hpp"

namespace eip2mqtt::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kEjabberdctl = "/usr/sbin/ejabberdctl";

/// Hands `path` and everything under it to the `ejabberd` user, as which the nodes run.
void give_to_ejabberd(const fs::path& path) {
    const passwd* user = ::getpwnam("ejabberd");
    if (user == nullptr) return;
    ::chown(path.c_str(), user->pw_uid, user->pw_gid);
    for (const auto& entry : fs::recursive_directory_iterator(path)) {
        ::chown(entry.path().c_str(), user->pw_uid, user->pw_gid);
    }
}

}  // namespace

bool EjabberdCluster::available() {
    // ejabberdctl runs its nodes as the ejabberd user only when started by root.
    return ::access(kEjabberdctl, X_OK) == 0 && ::geteuid() == 0;
}

EjabberdCluster::EjabberdCluster(int nodes) : BrokerCluster("ejabberd") { form(nodes, "eip2mqtt"); }

void EjabberdCluster::launch(Node& node) {
    fs::create_directories(node.dir + "/logs");
    fs::create_directories(node.dir + "/spool");
    // Only the MQTT listener: no XMPP port to collide with another node's.
    write_text_file(node.dir + "/ejabberd.yml",
                    "hosts: [localhost]\nloglevel: info\nauth_method: [anonymous]\n"
                    "anonymous_protocol: login_anon\nlisten:\n  - port: " +
                        std::to_string(node.port) +
                        "\n    ip: \"127.0.0.1\"\n    module: mod_mqtt\n    backlog: 1000\n"
                        "modules:\n  mod_mqtt: {}\n");
    // ejabberdctl reads this file after its arguments: the node's own pid file, and for the node
    // and every command sent to it the cluster's epmd and cookie (not the ejabberd user's cookie
    // file: two tests' clusters starting at once on a fresh machine would race to create it).
    write_text_file(node.dir + "/ejabberdctl.cfg",
                    "EJABBERD_PID_PATH=" + node.dir + "/pid\nERL_OPTIONS=\"-env " +
                        "ERL_CRASH_DUMP_BYTES 0 -setcookie " + cookie() + "\"\nERL_EPMD_PORT=" +
                        std::to_string(epmd_port()) + "\nexport ERL_EPMD_PORT\n");
    give_to_ejabberd(node.dir);
    auto argv = ctl(node);
    argv.push_back("foreground");
    node.process = std::make_unique<ChildProcess>(
        argv, std::map<std::string, std::string>{{"ERL_EPMD_PORT", std::to_string(epmd_port())}});
}

std::optional<std::string> EjabberdCluster::join(const Node& node, const Node& first) {
    auto argv = ctl(node);
    argv.insert(argv.end(), {"join_cluster", first.name});
    const auto joined = run_command(argv, kCommandDeadline);
    if (joined.status == 0) return std::nullopt;
    return joined.output;
}

std::vector<std::string> EjabberdCluster::ctl(const Node& node) const {
    return {kEjabberdctl,
            "--node",
            node.name,
            "--config-dir",
            node.dir,
            "--config",
            node.dir + "/ejabberd.yml",
            "--ctl-config",
            node.dir + "/ejabberdctl.cfg",
            "--logs",
            node.dir + "/logs",
            "--spool",
            node.dir + "/spool"};
}

std::string EjabberdCluster::log(int node) const {
    const auto& logged = *nodes().at(node);
    return read_text_file(logged.dir + "/logs/ejabberd.log") +
           (logged.process ? logged.process->output() : "");
}

std::string EjabberdCluster::members() const {
    for (const auto& node : nodes()) {
        if (node->vm <= 0) continue;
        auto argv = ctl(*node);
        argv.push_back("list_cluster");
        return run_command(argv, kCommandDeadline).output;
    }
    return "";
}

}  // namespace eip2mqtt::test
