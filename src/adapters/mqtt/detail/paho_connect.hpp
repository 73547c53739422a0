#pragma once
/// Paho C's TCP connects, completed where Paho starts them and noticed at once.
///
/// Why: a move to the next broker took 1.05 s longer than its backoff, for two waits inside
/// Paho C (Debian's 1.3.12):
/// - It starts a connect without blocking and learns that it completed only when its receive
///   thread's poll returns; that poll waits for something to read, up to a second, whatever it
///   knows about writable sockets, and a new connection has nothing to read before CONNECT.
/// - Its receive thread, with no socket at all (the connection just lost), sleeps 100 ms a turn,
///   and reads the new connection's CONNACK only at the end of its turn.
/// The process's `connect` and `usleep` are defined here (the executable's definitions come
/// before the C library's for every library it loads), and act differently only in Paho's
/// threads, which Paho names: in its send thread, a connect still in progress is waited for,
/// at most `paho_connect_wait`, and reported as done, which Paho handles by sending CONNECT (or
/// starting TLS) straight away; its receive thread's sleep ends early once a connect of the send
/// thread has a socket for it to read. Every other caller, a connect slower than the wait, and a
/// Paho that names its threads otherwise get the C library's behaviour unchanged.
///
/// Not for TLS: a connect Paho finds done at once takes another path through its TLS start,
/// which lost the broker's answer to CONNECT (a refused login reported as a bare failure, 5 of
/// 12 runs under AddressSanitizer). Connects to the port of a TLS broker are left as they are.
///
/// Module-private (src/adapters/mqtt/detail).

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {

/// How long Paho's send thread may wait for a TCP connect: a round trip on a plant's network
/// or to a nearby data centre. While it waits, no Paho connection sends, so it stays short; a
/// broker farther away connects as before, through Paho's poll.
inline constexpr std::chrono::milliseconds paho_connect_wait{25};

/// Waits up to `wait` for the non-blocking connect of `fd` to end: 0 when it connected; -1 with
/// errno the connect's error when it failed, or EINPROGRESS when it goes on.
int finish_connect(int fd, std::chrono::milliseconds wait);

/// Whether the calling thread is the Paho C thread named `name` (`MQTTAsync_send`, which starts
/// its connects, or `MQTTAsync_rcv`, which reads).
bool in_paho_thread(const char* name);

/// Says that the send thread has a new socket: the receive thread's sleep ends.
void paho_socket_added();

/// The receive thread's sleep: until paho_socket_added (one since the last sleep counts), at
/// most `limit`. Whether it ended early.
bool sleep_until_paho_socket(std::chrono::microseconds limit);

/// Marks `port` as a TLS broker's: Paho's connects to it keep the C library's behaviour.
void paho_tls_port(std::uint16_t port);
/// Whether a connect to `port` is left as it is (paho_tls_port).
bool is_paho_tls_port(std::uint16_t port);

/// Marks the TLS brokers' ports among `urls` (paho_tls_port), and keeps this file's `connect`
/// and `usleep` in every program that makes a Paho client (a static library's member is linked
/// only when something it defines is used); returns the wait.
std::chrono::milliseconds paho_connects_at_once(const std::vector<std::string>& urls);

}  // namespace eip2mqtt::adapters::mqtt::detail
