#pragma once
/// A TCP proxy that a test can stall, delay or cut: every connection made to it is carried to
/// `upstream_port` on 127.0.0.1. stall() holds everything while the connections stay open, as
/// behind a switch that died: neither end learns of it but by its own timeouts; resume() carries
/// on with what waited. Each direction can also be set on its own, at run time: delayed (what
/// it reads is written that much later, in order), stalled (nothing read, so what waits reaches
/// the other end when it is resumed) or cut (what it reads is thrown away: neither end hears of
/// it, and nothing of it ever arrives). A tap, when given, is told every byte read and every
/// close, for a relay that records what passes (mqtt_relay.hpp). A thread of its own, ended by
/// the destructor.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <string_view>
#include <thread>
#include <vector>

namespace eip2mqtt::test {

class TcpProxy {
public:
    /// to_server: from the clients to the upstream server; to_client: back.
    enum class Direction : std::uint8_t { to_server, to_client };
    /// Told on the proxy's thread of the bytes read in `direction` of connection `link`
    /// (numbered from 0 in the order taken), before any mode applies; and of its end, with
    /// `closed` set and no bytes: `direction`'s sender closed it (to_server: the client).
    using Tap = std::function<void(std::size_t link, Direction direction, std::string_view bytes,
                                   bool closed)>;

    /// Listens on an ephemeral port of 127.0.0.1.
    explicit TcpProxy(std::uint16_t upstream_port, Tap tap = nullptr);
    /// Takes `listener`, a socket already bound and listening (made inside a test's network
    /// namespace, say: the proxy's own connections upstream are made in the test's namespace).
    TcpProxy(std::uint16_t upstream_port, int listener);
    ~TcpProxy();
    TcpProxy(const TcpProxy&) = delete;
    TcpProxy& operator=(const TcpProxy&) = delete;

    std::uint16_t port() const { return port_; }
    /// From now on nothing passes and no connection is taken (the kernel's backlog holds them).
    void stall() { stalled_ = true; }
    /// From now on nothing passes from the connections' clients to the upstream port; what
    /// the upstream sends still passes (a cut in one direction).
    void stall_upstream() {
        upstream_stalled_ = true;
        set_mode(Direction::to_server, Mode::stall);
    }
    /// Ends stall() and stall_upstream(); modes set by set_mode() stay.
    void resume() {
        stalled_ = false;
        if (upstream_stalled_.exchange(false)) set_mode(Direction::to_server, Mode::pass);
    }
    /// Connections taken since the start.
    std::size_t connections() const { return connections_; }

    enum class Mode : std::uint8_t { pass, stall, cut };
    void set_mode(Direction direction, Mode mode) { modes_[index(direction)] = mode; }
    /// What is read in `direction` from now on is written `delay` later (0: at once).
    void set_delay(Direction direction, std::chrono::milliseconds delay) {
        delays_ms_[index(direction)] = delay.count();
    }

private:
    using Clock = std::chrono::steady_clock;
    struct Pending {
        Clock::time_point due;
        std::vector<char> bytes;
    };
    struct Link {
        std::size_t id = 0;
        int client = -1;
        int server = -1;
        std::array<std::deque<Pending>, 2> pending;  ///< per direction, oldest first
    };
    static std::size_t index(Direction d) { return static_cast<std::size_t>(d); }
    void start();
    void run();
    void accept_one();
    /// Reads what waits on the link's side for `direction`; false when that end closed.
    bool read(Link& link, Direction direction);
    /// Writes what is due; false when the other end is gone.
    bool flush(Link& link, Clock::time_point now);
    /// How long the poll may wait: until the next pending write is due, at most 20 ms.
    int poll_timeout(Clock::time_point now) const;

    int listener_ = -1;
    std::uint16_t upstream_port_;
    Tap tap_;
    std::uint16_t port_ = 0;
    std::atomic<bool> stalled_{false};
    std::array<std::atomic<Mode>, 2> modes_{Mode::pass, Mode::pass};
    std::array<std::atomic<long>, 2> delays_ms_{0, 0};
    std::atomic<bool> upstream_stalled_{false};
    std::atomic<bool> stop_{false};
    std::atomic<std::size_t> connections_{0};
    std::vector<Link> links_;  ///< the proxy's thread only
    std::thread thread_;
};

}  // namespace eip2mqtt::test
