#include "tests/support/broker_cluster.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <thread>

#include "tests/support/ejabberd_cluster.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/rabbitmq_cluster.hpp"
#include "tests/support/text_file.hpp"

namespace eip2mqtt::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr const char* kEpmd = "/usr/bin/epmd";
// An Erlang VM and its broker start in seconds on an idle machine (RabbitMQ's in about 20);
// far more with three starting at once on a loaded one.
constexpr auto kStartDeadline = 180s;

/// Polls `done` every 50 ms until it holds (true) or `deadline` passes (false).
template <class Condition>
bool poll_until(Condition done, std::chrono::milliseconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!done()) {
        if (std::chrono::steady_clock::now() > until) return false;
        std::this_thread::sleep_for(50ms);
    }
    return true;
}

}  // namespace

std::string BrokerCluster::name(Kind kind) {
    return kind == Kind::ejabberd ? "ejabberd" : "rabbitmq";
}

bool BrokerCluster::available(Kind kind) {
    return kind == Kind::ejabberd ? EjabberdCluster::available() : RabbitmqCluster::available();
}

std::unique_ptr<BrokerCluster> BrokerCluster::start(Kind kind, int nodes) {
    if (!available(kind)) return nullptr;
    if (kind == Kind::ejabberd) return std::make_unique<EjabberdCluster>(nodes);
    return std::make_unique<RabbitmqCluster>(nodes);
}

BrokerCluster::BrokerCluster(const std::string& broker) {
    std::string name = "/tmp/eip2mqtt-" + broker + "-XXXXXX";
    if (::mkdtemp(name.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    dir_ = name;
    ::chmod(dir_.c_str(), 0755);
    epmd_port_ = free_tcp_port();
    epmd_ = std::make_unique<ChildProcess>(std::vector<std::string>{
        kEpmd, "-port", std::to_string(epmd_port_), "-address", "127.0.0.1"});
}

std::string BrokerCluster::cookie() const { return "eip2mqtt" + std::to_string(::getpid()); }

void BrokerCluster::form(int nodes, const std::string& name_prefix) {
    if (!poll_until([&] { return accepts_connections(epmd_port_); }, 10s)) {
        ADD_FAILURE() << "epmd did not start: " << epmd_->output();
        return;
    }
    for (int i = 0; i < nodes; ++i) {
        auto node = std::make_unique<Node>();
        node->name =
            name_prefix + std::to_string(::getpid()) + "n" + std::to_string(i) + "@localhost";
        node->dir = dir_ + "/n" + std::to_string(i);
        node->port = free_tcp_port();
        fs::create_directories(node->dir);
        launch(*node);
        nodes_.push_back(std::move(node));
    }
    for (int i = 0; i < size(); ++i) {
        if (!wait_started(i)) return;
    }
    for (std::size_t i = 1; i < nodes_.size(); ++i) {
        if (const auto failed = join(*nodes_[i], *nodes_.front())) {
            ADD_FAILURE() << nodes_[i]->name << " did not join: " << *failed;
            return;
        }
    }
    // A joined node may have restarted its broker (RabbitMQ's stop_app and start_app).
    for (const auto& node : nodes_) {
        if (!poll_until([&] { return accepts_connections(node->port); }, kStartDeadline)) {
            ADD_FAILURE() << node->name << " takes no MQTT connection after joining";
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

bool BrokerCluster::wait_started(int index) {
    auto& node = *nodes_.at(index);
    const bool started = poll_until(
        [&] {
            const auto pid = read_text_file(node.dir + "/pid");
            if (!pid.empty()) node.vm = static_cast<pid_t>(std::stol(pid));
            return node.vm > 0 && accepts_connections(node.port);
        },
        kStartDeadline);
    if (!started) {
        ADD_FAILURE() << node.name << " did not start: " << log(index);
        node.vm = -1;
    }
    return started;
}

BrokerCluster::~BrokerCluster() {
    for (const auto& node : nodes_) {
        if (node->vm > 0) ::kill(node->vm, SIGKILL);
    }
    nodes_.clear();  // each launcher ends with its VM, or is killed
    epmd_.reset();
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
}

std::uint16_t BrokerCluster::port(int node) const { return nodes_.at(node)->port; }

std::string BrokerCluster::url(int node) const {
    return "tcp://127.0.0.1:" + std::to_string(port(node));
}

std::string BrokerCluster::url_list(int first) const {
    std::string list;
    for (int i = 0; i < size(); ++i) {
        list += (i == 0 ? "[ \"" : ", \"") + url((first + i) % size()) + "\"";
    }
    return list + " ]";
}

std::string BrokerCluster::mqtt_keys() const {
    const auto given = login();
    return "  username: " + given.username + "\n" +
           (given.version == 4 ? "  version: \"3.1.1\"\n" : "");
}

void BrokerCluster::kill(int node) {
    auto& killed = *nodes_.at(node);
    if (killed.vm <= 0) return;
    ::kill(killed.vm, SIGKILL);
    killed.vm = -1;
    EXPECT_TRUE(poll_until([&] { return !accepts_connections(killed.port); }, 30s))
        << killed.name << " still accepts connections";
    killed.process->wait(30s);
}

}  // namespace eip2mqtt::test
