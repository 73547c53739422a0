#include "tests/support/net_namespace.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sched.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "tests/support/child_process.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

// run_command execs by path; iproute2 installs it here (tools/install-deps.sh). Commands run
// inside a namespace go through `ip netns exec`, which searches PATH itself.
constexpr const char* ip_path = "/usr/sbin/ip";

RunResult ip(std::vector<std::string> argv) {
    argv.insert(argv.begin(), ip_path);
    return run_command(std::move(argv), 10s);
}

std::string probe() {
    if (::geteuid() != 0) return "network namespaces need root (CAP_NET_ADMIN, CAP_SYS_ADMIN)";
    const auto name = "e2m" + std::to_string(::getpid()) + "-probe";
    const auto added = ip({"netns", "add", name});
    if (added.status != 0) return "`ip netns add` failed: " + added.output;
    const auto rule = ip({"netns", "exec", name, "iptables", "-A", "INPUT", "-j", "DROP"});
    ip({"netns", "del", name});
    if (rule.status != 0) {
        return "iptables does not run in a namespace (tools/install-deps.sh installs it): " +
               rule.output;
    }
    return "";
}

}  // namespace

const std::string& NetNamespace::unavailable() {
    static const std::string why = probe();
    return why;
}

NetNamespace::NetNamespace(const std::string& tag)
    : tag_(tag), name_("e2m" + std::to_string(::getpid()) + "-" + tag) {
    const auto added = ip({"netns", "add", name_});
    if (added.status != 0) throw std::runtime_error("ip netns add " + name_ + ": " + added.output);
    run({"ip", "link", "set", "lo", "up"});
}

NetNamespace::~NetNamespace() { ip({"netns", "del", name_}); }

std::vector<std::string> NetNamespace::inside(const std::vector<std::string>& argv) const {
    std::vector<std::string> out{ip_path, "netns", "exec", name_};
    out.insert(out.end(), argv.begin(), argv.end());
    return out;
}

void NetNamespace::run(const std::vector<std::string>& argv) const {
    const auto result = run_command(inside(argv), 10s);
    if (result.status != 0) {
        std::string command;
        for (const auto& a : argv) command += " " + a;
        throw std::runtime_error("in " + name_ + ":" + command + ": " + result.output);
    }
}

int NetNamespace::socket(int domain, int type, int protocol) const {
    int fd = -1;
    // setns changes only the calling thread's namespace: a thread of its own, ended at once.
    std::thread([&] {
        const int ns = ::open(("/var/run/netns/" + name_).c_str(), O_RDONLY | O_CLOEXEC);
        if (ns < 0) return;
        if (::setns(ns, CLONE_NEWNET) == 0) fd = ::socket(domain, type | SOCK_CLOEXEC, protocol);
        ::close(ns);
    }).join();
    return fd;
}

int NetNamespace::listen_tcp(const std::string& address) const {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in where{};
    where.sin_family = AF_INET;
    if (fd < 0 || ::inet_pton(AF_INET, address.c_str(), &where.sin_addr) != 1 ||
        ::bind(fd, reinterpret_cast<sockaddr*>(&where), sizeof where) != 0 ||
        ::listen(fd, 16) != 0) {
        if (fd >= 0) ::close(fd);
        throw std::runtime_error("cannot listen on " + address + " in " + name_);
    }
    return fd;
}

void NetNamespace::cut(bool tcp_only) {
    heal();
    std::vector<std::string> protocol;
    if (tcp_only) protocol = {"-p", "tcp"};
    for (const std::string chain : {"INPUT", "OUTPUT"}) {
        std::vector<std::string> rule{"iptables", "-A", chain, "!", chain == "INPUT" ? "-i" : "-o",
                                      "lo"};
        rule.insert(rule.end(), protocol.begin(), protocol.end());
        rule.insert(rule.end(), {"-j", "DROP"});
        run(rule);
    }
}

void NetNamespace::heal() {
    run({"iptables", "-F", "INPUT"});
    run({"iptables", "-F", "OUTPUT"});
}

void NetNamespace::link_to(const NetNamespace& peer, const std::string& address,
                           const std::string& peer_address) const {
    const auto here = "to-" + peer.tag_;
    const auto there = "to-" + tag_;
    run({"ip", "link", "add", here, "type", "veth", "peer", "name", there, "netns", peer.name_});
    run({"ip", "addr", "add", address + "/24", "dev", here});
    run({"ip", "link", "set", here, "up"});
    peer.run({"ip", "addr", "add", peer_address + "/24", "dev", there});
    peer.run({"ip", "link", "set", there, "up"});
    run({"ip", "route", "add", "default", "via", peer_address});
}

}  // namespace eip2mqtt::test
