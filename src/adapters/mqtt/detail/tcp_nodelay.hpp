#pragma once
/// Finds this process's TCP connections to the broker and switches TCP_NODELAY on them.
///
/// Why: Debian 12's Paho MQTT C (1.3.12) never sets TCP_NODELAY, so Nagle's algorithm holds a
/// small QoS 0 publication back until the broker's delayed ACK of the previous one, which sets
/// the latency's tail. Yet Nagle is what packs a backlog of small publications into few TCP
/// segments, which the broker reads far more cheaply than one segment per publication. So the
/// client keeps TCP_NODELAY on while it keeps up (no publication waits) and turns it off only
/// while a backlog is being sent; turning it back on pushes out what Nagle held (Linux calls
/// tcp_push_pending_frames when TCP_NODELAY is set).
///
/// Paho does not expose its socket, so we find it: every fd in /proc/self/fd that is a
/// SOCK_STREAM socket whose peer is one of the broker's resolved addresses and port. Another
/// client of the same broker in this process (a test's recorder) is switched too, which does it
/// no harm.
///
/// Module-private (src/adapters/mqtt/detail).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {

/// Resolves `host` (blocking getaddrinfo; numeric hosts resolve instantly) and returns this
/// process's TCP sockets connected to it.
std::vector<int> sockets_connected_to(const std::string& host, std::uint16_t port);

/// Sets TCP_NODELAY to `on` on `fd`; false when the kernel refused (fd closed or reused).
bool set_tcp_nodelay(int fd, bool on);

/// TCP_NODELAY of the broker connection, switched by whoever sends: on while idle, off while a
/// backlog is sent. Thread-safe; a setsockopt only when the wanted state changes.
class NagleSwitch {
public:
    /// After a connect: these sockets get TCP_NODELAY now; later calls switch them.
    void attach(std::vector<int> fds);
    /// After a connection loss: forget the sockets (their fds may be reused).
    void detach();
    /// true: a backlog is being sent (Nagle on); false: caught up (TCP_NODELAY on, flushes).
    void set_backlogged(bool backlogged);

private:
    std::mutex mutex_;
    std::vector<int> fds_;
    bool backlogged_ = false;
    std::atomic<bool> wanted_backlogged_{false};
};

}  // namespace eip2mqtt::adapters::mqtt::detail
