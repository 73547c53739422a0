#pragma once
/// A TCP proxy on loopback that a test can stall: every connection made to it is carried to
/// `upstream_port` on 127.0.0.1 until stall(), when nothing more passes either way while the
/// connections stay open, as behind a switch that died: neither end learns of it but by its own
/// timeouts. resume() carries on with what waited. A thread of its own, ended by the destructor.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace eip2mqtt::test {

class TcpProxy {
public:
    explicit TcpProxy(std::uint16_t upstream_port);
    ~TcpProxy();
    TcpProxy(const TcpProxy&) = delete;
    TcpProxy& operator=(const TcpProxy&) = delete;

    std::uint16_t port() const { return port_; }
    /// From now on nothing passes and no connection is taken (the kernel's backlog holds them).
    void stall() { stalled_ = true; }
    /// From now on nothing passes from the connections' clients to the upstream port; what
    /// the upstream sends still passes (a cut in one direction).
    void stall_upstream() { upstream_stalled_ = true; }
    void resume() {
        stalled_ = false;
        upstream_stalled_ = false;
    }
    /// Connections taken since the start.
    std::size_t connections() const { return connections_; }

private:
    struct Link {
        int client = -1;
        int server = -1;
    };
    void run();
    void accept_one();
    /// Copies what waits on `from` to `to`; false when either end closed.
    static bool pass(int from, int to);

    int listener_ = -1;
    std::uint16_t upstream_port_;
    std::uint16_t port_ = 0;
    std::atomic<bool> stalled_{false};
    std::atomic<bool> upstream_stalled_{false};
    std::atomic<bool> stop_{false};
    std::atomic<std::size_t> connections_{0};
    std::vector<Link> links_;  ///< the proxy's thread only
    std::thread thread_;
};

}  // namespace eip2mqtt::test
