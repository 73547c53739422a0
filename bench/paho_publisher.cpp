// paho_publisher: the bare MQTT ceiling: a Paho C++ async client publishing messages shaped like
// the gateway's ({"value":V,"timestamp":MS,"quality":"good"} on {base}/e1/t{i}) at a chosen QoS
// to the same Mosquitto, with a window of publications in flight (like the gateway's
// max_in_flight, within the broker's Receive Maximum at QoS >= 1), so that Paho's own queue
// stays bounded. Nothing else: no TCP_NODELAY, no coalescing. Paho C's in-memory trace is
// turned down to errors as the gateway turns it down (the same function,
// adapters/mqtt/detail/paho_trace.hpp): the baseline is Paho as the gateway runs it, so a row's
// ratio is the gateway's own cost. A plain Paho application, trace left at Debian's default,
// sends less (docs/performance.md says how much).
//
// --rate 0 publishes as fast as the window allows; --rate R paces in 1 ms batches against
// absolute deadlines. --stamp puts CLOCK_REALTIME ns in every value (for latency, read by
// mqtt_counter --stamp-all). Prints one JSON line: published, completed, failed, elapsed_s,
// drained_s, rate, window (the one used).

#include <mqtt/async_client.h>

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "adapters/mqtt/detail/paho_trace.hpp"
#include "bench_common.hpp"

namespace {

struct Window final : mqtt::iaction_listener {
    std::mutex mutex;
    std::condition_variable done;
    std::size_t outstanding = 0;
    std::atomic<std::uint64_t> completed{0};
    std::atomic<std::uint64_t> failed{0};

    void finish(bool ok) {
        (ok ? completed : failed).fetch_add(1, std::memory_order_relaxed);
        {
            std::lock_guard lock(mutex);
            --outstanding;
        }
        done.notify_one();
    }
    void on_success(const mqtt::token&) override { finish(true); }
    void on_failure(const mqtt::token&) override { finish(false); }
};

struct Settings {
    std::string url;
    int qos = 0;
    std::vector<std::string> topics;
    std::size_t window = 0;  ///< publications in flight per connection, as requested
    double rate = 0;
    bool stamp = false;
    bool v5 = true;
    std::uint64_t count = 0;
    std::int64_t duration_ns = 0;
    std::size_t connections = 1;
    std::string id;
};

Settings read_settings(int argc, char** argv) {
    const bench::Options opt(argc, argv,
                             {"url", "qos", "topics", "base", "count", "duration", "rate", "window",
                              "stamp", "version", "id", "connections"});
    Settings s;
    s.url = opt.str("url", "tcp://127.0.0.1:1883");
    s.qos = static_cast<int>(opt.num("qos", 0));
    const auto topics = static_cast<std::size_t>(std::max(1.0, opt.num("topics", 100)));
    const std::string base = opt.str("base", "p");
    for (std::size_t i = 0; i < topics; ++i) s.topics.push_back(base + "/e1/t" + std::to_string(i));
    s.window = static_cast<std::size_t>(opt.num("window", 1000));
    s.rate = opt.num("rate", 0);
    s.stamp = opt.has("stamp");
    s.v5 = opt.num("version", 5) == 5;
    s.count = static_cast<std::uint64_t>(opt.num("count", 0));
    s.duration_ns = static_cast<std::int64_t>(opt.num("duration", 5) * 1e9);
    // --connections N: N clients of one process (Paho C's send and receive threads are the
    // process's, shared by its clients), each topic always on the same one.
    s.connections = static_cast<std::size_t>(std::max(1.0, opt.num("connections", 1)));
    // --id: a client identifier of its own for each of several publishers on one broker.
    s.id = opt.str("id", "bench-paho-publisher");
    return s;
}

/// The clients, connected; the window within which publications stay (the requested one, or
/// less where the broker says).
struct Clients {
    std::vector<std::unique_ptr<mqtt::async_client>> clients;
    std::size_t window = 0;
};

Clients connect_clients(const Settings& s) {
    Clients out;
    out.window = s.window;
    mqtt::create_options create(s.v5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    create.set_max_buffered_messages(static_cast<int>(s.window + 64));
    for (std::size_t c = 0; c < s.connections; ++c) {
        out.clients.push_back(std::make_unique<mqtt::async_client>(
            s.url, s.connections == 1 ? s.id : s.id + "-" + std::to_string(c), create, nullptr));
    }
    mqtt::connect_options connect;
    connect.set_mqtt_version(s.v5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    if (s.v5) {
        connect.set_clean_start(true);
    } else {
        connect.set_clean_session(true);
    }
    try {
        for (auto& client : out.clients) {
            auto token = client->connect(connect);
            token->wait_for(std::chrono::seconds(10));
            // MQTT 5: the broker's Receive Maximum bounds the QoS >= 1 publications in flight
            // (Mosquitto's default is 20). Paho C holds any beyond it in its queue until its
            // next one-second cycle, so a plain application that ignored it would measure
            // Paho's timer, not the broker: stay within it, as the gateway does.
            const auto response = token->get_connect_response();
            const auto& props = response.get_properties();
            if (s.v5 && s.qos > 0 && props.contains(mqtt::property::RECEIVE_MAXIMUM)) {
                out.window = std::min<std::size_t>(
                    out.window, mqtt::get<std::uint16_t>(props, mqtt::property::RECEIVE_MAXIMUM));
            }
        }
    } catch (const mqtt::exception& e) {
        bench::Options::fail(std::string("connect: ") + e.what());
    }
    return out;
}

/// Publishes on the topics in turn, each connection within its window.
class Publisher {
public:
    Publisher(const Settings& s, Clients& clients) : s_(s), clients_(clients) {
        for (std::size_t c = 0; c < s.connections; ++c) {
            windows_.push_back(std::make_unique<Window>());
        }
    }

    /// Publishes until the count or the duration is reached; returns the seconds taken.
    double run() {
        start_ = bench::mono_ns();
        if (s_.rate <= 0) {
            while (more(bench::mono_ns())) publish_one();
        } else {
            constexpr std::int64_t batch_ns = 1000000;
            for (std::int64_t batch = 1;; ++batch) {
                const std::int64_t now = bench::mono_ns();
                if (!more(now)) break;
                auto due = static_cast<std::uint64_t>(static_cast<double>(batch) * batch_ns *
                                                      s_.rate / 1e9);
                if (s_.count > 0) due = std::min(due, s_.count);
                while (published_ < due) publish_one();
                const std::int64_t deadline = start_ + batch * batch_ns;
                if (bench::mono_ns() < deadline) bench::sleep_until_mono(deadline);
            }
        }
        return static_cast<double>(bench::mono_ns() - start_) / 1e9;
    }

    /// Waits for the publications in flight (30 s at most each window); returns the seconds
    /// since the start.
    double drain() {
        for (auto& window : windows_) {
            std::unique_lock lock(window->mutex);
            window->done.wait_for(lock, std::chrono::seconds(30),
                                  [&] { return window->outstanding == 0; });
        }
        return static_cast<double>(bench::mono_ns() - start_) / 1e9;
    }

    std::uint64_t published() const { return published_; }
    std::uint64_t completed() const { return sum(&Window::completed); }
    std::uint64_t failed() const { return sum(&Window::failed); }

private:
    bool more(std::int64_t now) const {
        return s_.count > 0 ? published_ < s_.count : now - start_ < s_.duration_ns;
    }

    void publish_one() {
        // Stamped when the application has the value, before any wait for room in the window:
        // that wait is the broker's flow control, part of the latency a subscriber sees, and the
        // gateway's figure includes it (its stamp is the datagram's send time).
        const std::int64_t wall = bench::wall_ns();
        const std::size_t topic = published_ % s_.topics.size();
        Window& window = *windows_[topic % s_.connections];
        {
            std::unique_lock lock(window.mutex);
            window.done.wait(lock, [&] { return window.outstanding < clients_.window; });
            ++window.outstanding;
        }
        const long long value = s_.stamp ? wall : static_cast<long long>(published_ % 1000000000);
        std::string payload = "{\"value\":" + std::to_string(value) +
                              ",\"timestamp\":" + std::to_string(wall / 1000000) +
                              ",\"quality\":\"good\"}";
        try {
            clients_.clients[topic % s_.connections]->publish(
                mqtt::make_message(s_.topics[topic], std::move(payload), s_.qos, false), nullptr,
                window);
        } catch (const mqtt::exception&) {
            window.finish(false);
        }
        ++published_;
    }

    std::uint64_t sum(std::atomic<std::uint64_t> Window::*counter) const {
        std::uint64_t total = 0;
        for (const auto& window : windows_) total += ((*window).*counter).load();
        return total;
    }

    const Settings& s_;
    Clients& clients_;
    std::vector<std::unique_ptr<Window>> windows_;  // one per connection
    std::uint64_t published_ = 0;
    std::int64_t start_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    const Settings s = read_settings(argc, argv);
    eip2mqtt::adapters::mqtt::detail::quiet_paho_trace(std::getenv("MQTT_C_CLIENT_TRACE"));
    Clients clients = connect_clients(s);
    Publisher publisher(s, clients);
    const double elapsed = publisher.run();
    const double drained = publisher.drain();
    const std::uint64_t completed = publisher.completed();
    const std::uint64_t failed = publisher.failed();
    for (auto& client : clients.clients) {
        try {
            client->disconnect()->wait_for(std::chrono::seconds(5));
        } catch (const mqtt::exception&) {
        }
    }
    std::printf(
        "{\"published\":%llu,\"completed\":%llu,\"failed\":%llu,\"elapsed_s\":%.4f,"
        "\"drained_s\":%.4f,\"rate\":%.1f,\"window\":%zu,\"connections\":%zu}\n",
        static_cast<unsigned long long>(publisher.published()),
        static_cast<unsigned long long>(completed), static_cast<unsigned long long>(failed),
        elapsed, drained, static_cast<double>(completed) / drained, clients.window, s.connections);
    return 0;
}
