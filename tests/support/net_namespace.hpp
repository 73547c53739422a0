#pragma once
/// Network namespaces made by a test, for faults no loopback test can make: a unit of a pair in
/// a namespace of its own, joined to the test's segment namespace by a veth pair, can be cut off
/// by `iptables` DROP rules inside its namespace, in both directions, which tell neither end
/// (no reset, no ICMP: what is sent is lost, as behind a dead switch). Addresses are given only
/// inside the test's namespaces; nothing is sent outside them but to 127.0.0.0/8. Needs root (or
/// CAP_NET_ADMIN and CAP_SYS_ADMIN), `ip` and `iptables`: a test asks unavailable() first and
/// skips, saying why, where they are missing.

#include <string>
#include <vector>

namespace eip2mqtt::test {

class NetNamespace {
public:
    /// Empty when this process can make a namespace and add an iptables rule inside it; else
    /// what is missing, for GTEST_SKIP. Tried once, then remembered.
    static const std::string& unavailable();

    /// Adds namespace `e2m<pid>-<tag>` with its loopback up. Throws when `ip` fails.
    explicit NetNamespace(const std::string& tag);
    /// Deletes it (its veth ends with it, and the processes still in it lose their network).
    ~NetNamespace();
    NetNamespace(const NetNamespace&) = delete;
    NetNamespace& operator=(const NetNamespace&) = delete;

    const std::string& name() const { return name_; }
    /// `argv` run inside the namespace (`ip netns exec NAME argv...`), for ChildProcess: the
    /// pid is the program's own, since `ip` execs it.
    std::vector<std::string> inside(const std::vector<std::string>& argv) const;
    /// Runs `argv` inside to completion; throws with its output when it fails.
    void run(const std::vector<std::string>& argv) const;
    /// A socket made inside the namespace (socket(2)'s arguments; -1 on failure): it stays in
    /// the namespace, whichever thread then uses it.
    int socket(int domain, int type, int protocol) const;
    /// A listening TCP socket on `address` (dotted IPv4), an ephemeral port, inside.
    int listen_tcp(const std::string& address) const;

    /// Drops everything in and out of this namespace (`tcp_only`: only TCP, the path to the
    /// broker, while datagrams still pass), until heal(). Loopback inside is left alone.
    void cut(bool tcp_only);
    void heal();

    /// Joins this namespace to `peer` by a veth pair: `address` here and `peer_address` there
    /// (dotted, in one /24); this side's default route goes through the peer.
    void link_to(const NetNamespace& peer, const std::string& address,
                 const std::string& peer_address) const;

private:
    std::string tag_;
    std::string name_;
};

}  // namespace eip2mqtt::test
