#include "tests/support/ejabberd_cluster.hpp"

#include <gtest/gtest.h>
#include <pwd.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "tests/support/free_port.hpp"
#include "tests/support/text_file.hpp"

namespace eip2mqtt::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr const char* kEjabberdctl = "/usr/sbin/ejabberdctl";
constexpr const char* kEpmd = "/usr/bin/epmd";
// An Erlang VM and ejabberd start in a few seconds on an idle machine; far more on a loaded one.
constexpr auto kStartDeadline = 90s;
constexpr auto kCommandDeadline = 90s;

/// Hands `path` and everything under it to the `ejabberd` user, as which the nodes run.
void give_to_ejabberd(const fs::path& path) {
    const passwd* user = ::getpwnam("ejabberd");
    if (user == nullptr) return;
    ::chown(path.c_str(), user->pw_uid, user->pw_gid);
    for (const auto& entry : fs::recursive_directory_iterator(path)) {
        ::chown(entry.path().c_str(), user->pw_uid, user->pw_gid);
    }
}

template <class Condition>
bool wait_until(Condition done, std::chrono::seconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!done()) {
        if (std::chrono::steady_clock::now() > until) return false;
        std::this_thread::sleep_for(50ms);
    }
    return true;
}

}  // namespace

struct EjabberdCluster::Node {
    std::string name;
    std::string dir;
    std::uint16_t port = 0;
    std::unique_ptr<ChildProcess> process;  ///< ejabberdctl foreground (su, sh, erl)
    pid_t vm = -1;                          ///< the Erlang VM, from its pid file
};

bool EjabberdCluster::available() {
    // ejabberdctl runs its nodes as the ejabberd user only when started by root.
    return ::access(kEjabberdctl, X_OK) == 0 && ::geteuid() == 0;
}

EjabberdCluster::EjabberdCluster(int nodes) {
    char name[] = "/tmp/eip2mqtt-ejabberd-XXXXXX";
    if (::mkdtemp(name) == nullptr) throw std::runtime_error("mkdtemp failed");
    dir_ = name;
    ::chmod(dir_.c_str(), 0755);
    epmd_port_ = free_tcp_port();
    epmd_ = std::make_unique<ChildProcess>(std::vector<std::string>{
        kEpmd, "-port", std::to_string(epmd_port_), "-address", "127.0.0.1"});
    if (!wait_until([&] { return accepts_connections(epmd_port_); }, 10s)) {
        ADD_FAILURE() << "epmd did not start: " << epmd_->output();
        return;
    }
    for (int i = 0; i < nodes; ++i) {
        auto node = std::make_unique<Node>();
        node->name =
            "eip2mqtt" + std::to_string(::getpid()) + "n" + std::to_string(i) + "@localhost";
        node->dir = dir_ + "/n" + std::to_string(i);
        node->port = free_tcp_port();
        start_node(*node);
        nodes_.push_back(std::move(node));
        if (nodes_.back()->vm < 0) return;
    }
    for (std::size_t i = 1; i < nodes_.size(); ++i) {
        auto join = ctl(*nodes_[i]);
        join.insert(join.end(), {"join_cluster", nodes_.front()->name});
        const auto joined = run_command(join, kCommandDeadline);
        if (joined.status != 0) {
            ADD_FAILURE() << nodes_[i]->name << " did not join: " << joined.output;
            return;
        }
    }
    const auto listed = members();
    for (const auto& node : nodes_) {
        if (listed.find(node->name) == std::string::npos) {
            ADD_FAILURE() << node->name << " is not in the cluster: " << listed;
            return;
        }
    }
    ready_ = true;
}

void EjabberdCluster::start_node(Node& node) {
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
    write_text_file(
        node.dir + "/ejabberdctl.cfg",
        "EJABBERD_PID_PATH=" + node.dir + "/pid\nERL_OPTIONS=\"-env ERL_CRASH_DUMP_BYTES 0" +
            " -setcookie eip2mqtt" + std::to_string(::getpid()) +
            "\"\nERL_EPMD_PORT=" + std::to_string(epmd_port_) + "\nexport ERL_EPMD_PORT\n");
    give_to_ejabberd(node.dir);
    auto argv = ctl(node);
    argv.push_back("foreground");
    node.process = std::make_unique<ChildProcess>(
        argv, std::map<std::string, std::string>{{"ERL_EPMD_PORT", std::to_string(epmd_port_)}});
    const bool started = wait_until(
        [&] {
            const auto pid = read_text_file(node.dir + "/pid");
            if (!pid.empty()) node.vm = static_cast<pid_t>(std::stol(pid));
            return node.vm > 0 && accepts_connections(node.port);
        },
        kStartDeadline);
    if (!started) {
        ADD_FAILURE() << node.name << " did not start: " << node.process->output();
        node.vm = -1;
    }
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

EjabberdCluster::~EjabberdCluster() {
    for (const auto& node : nodes_) {
        if (node->vm > 0) ::kill(node->vm, SIGKILL);
    }
    nodes_.clear();  // each ejabberdctl ends with its VM, or is killed
    epmd_.reset();
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
}

std::uint16_t EjabberdCluster::port(int node) const { return nodes_.at(node)->port; }

std::string EjabberdCluster::url(int node) const {
    return "tcp://127.0.0.1:" + std::to_string(port(node));
}

std::string EjabberdCluster::url_list(int first) const {
    std::string list;
    for (int i = 0; i < size(); ++i) {
        list += (i == 0 ? "[ \"" : ", \"") + url((first + i) % size()) + "\"";
    }
    return list + " ]";
}

void EjabberdCluster::kill(int node) {
    auto& killed = *nodes_.at(node);
    if (killed.vm <= 0) return;
    ::kill(killed.vm, SIGKILL);
    killed.vm = -1;
    EXPECT_TRUE(wait_until([&] { return !accepts_connections(killed.port); }, 30s))
        << killed.name << " still accepts connections";
    killed.process->wait(30s);
}

std::string EjabberdCluster::log(int node) const {
    const auto& logged = *nodes_.at(node);
    return read_text_file(logged.dir + "/logs/ejabberd.log") + logged.process->output();
}

std::string EjabberdCluster::members() const {
    for (const auto& node : nodes_) {
        if (node->vm <= 0) continue;
        auto argv = ctl(*node);
        argv.push_back("list_cluster");
        return run_command(argv, kCommandDeadline).output;
    }
    return "";
}

}  // namespace eip2mqtt::test
