// paho_publisher: the bare MQTT ceiling: a Paho C++ async client publishing messages shaped like
// the gateway's ({"value":V,"timestamp":MS,"quality":"good"} on {base}/e1/t{i}) at a chosen QoS
// to the same Mosquitto, with a window of publications in flight (like the gateway's
// max_in_flight, within the broker's Receive Maximum at QoS >= 1), so that Paho's own queue
// stays bounded. Nothing else: no TCP_NODELAY, no coalescing; this is what a plain Paho
// application gets.
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

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(argc, argv,
                             {"url", "qos", "topics", "base", "count", "duration", "rate", "window",
                              "stamp", "version", "id", "connections"});
    const std::string url = opt.str("url", "tcp://127.0.0.1:1883");
    const int qos = static_cast<int>(opt.num("qos", 0));
    const auto topics_n = static_cast<std::size_t>(std::max(1.0, opt.num("topics", 100)));
    const std::string base = opt.str("base", "p");
    const auto requested_window = static_cast<std::size_t>(opt.num("window", 1000));
    const double rate = opt.num("rate", 0);
    const bool stamp = opt.has("stamp");
    const bool v5 = opt.num("version", 5) == 5;
    const auto count = static_cast<std::uint64_t>(opt.num("count", 0));
    const auto duration_ns = static_cast<std::int64_t>(opt.num("duration", 5) * 1e9);

    std::vector<std::string> topics;
    for (std::size_t i = 0; i < topics_n; ++i) {
        topics.push_back(base + "/e1/t" + std::to_string(i));
    }

    // --connections N: N clients of one process (Paho C's send and receive threads are the
    // process's, shared by its clients), each topic always on the same one.
    const auto connections = static_cast<std::size_t>(std::max(1.0, opt.num("connections", 1)));
    mqtt::create_options create(v5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    create.set_max_buffered_messages(static_cast<int>(requested_window + 64));
    // --id: a client identifier of its own for each of several publishers on one broker.
    const std::string id = opt.str("id", "bench-paho-publisher");
    std::vector<std::unique_ptr<mqtt::async_client>> clients;
    for (std::size_t c = 0; c < connections; ++c) {
        clients.push_back(std::make_unique<mqtt::async_client>(
            url, connections == 1 ? id : id + "-" + std::to_string(c), create, nullptr));
    }
    mqtt::connect_options connect;
    connect.set_mqtt_version(v5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    if (v5) {
        connect.set_clean_start(true);
    } else {
        connect.set_clean_session(true);
    }
    std::size_t window_size = requested_window;
    try {
        for (auto& client : clients) {
            auto token = client->connect(connect);
            token->wait_for(std::chrono::seconds(10));
            // MQTT 5: the broker's Receive Maximum bounds the QoS >= 1 publications in flight
            // (Mosquitto's default is 20). Paho C holds any beyond it in its queue until its
            // next one-second cycle, so a plain application that ignored it would measure
            // Paho's timer, not the broker: stay within it, as the gateway does.
            const auto response = token->get_connect_response();
            const auto& props = response.get_properties();
            if (v5 && qos > 0 && props.contains(mqtt::property::RECEIVE_MAXIMUM)) {
                window_size = std::min<std::size_t>(
                    window_size, mqtt::get<std::uint16_t>(props, mqtt::property::RECEIVE_MAXIMUM));
            }
        }
    } catch (const mqtt::exception& e) {
        bench::Options::fail(std::string("connect: ") + e.what());
    }

    std::vector<std::unique_ptr<Window>> windows;  // one per connection
    for (std::size_t c = 0; c < connections; ++c) windows.push_back(std::make_unique<Window>());
    std::uint64_t published = 0;
    auto publish_one = [&] {
        // Stamped when the application has the value, before any wait for room in the window:
        // that wait is the broker's flow control, part of the latency a subscriber sees, and the
        // gateway's figure includes it (its stamp is the datagram's send time).
        const std::int64_t wall = bench::wall_ns();
        const std::size_t topic = published % topics_n;
        Window& window = *windows[topic % connections];
        {
            std::unique_lock lock(window.mutex);
            window.done.wait(lock, [&] { return window.outstanding < window_size; });
            ++window.outstanding;
        }
        const long long value = stamp ? wall : static_cast<long long>(published % 1000000000);
        std::string payload = "{\"value\":" + std::to_string(value) +
                              ",\"timestamp\":" + std::to_string(wall / 1000000) +
                              ",\"quality\":\"good\"}";
        try {
            clients[topic % connections]->publish(
                mqtt::make_message(topics[topic], std::move(payload), qos, false), nullptr, window);
        } catch (const mqtt::exception&) {
            window.finish(false);
        }
        ++published;
    };

    const std::int64_t start = bench::mono_ns();
    auto more = [&](std::int64_t now) {
        return count > 0 ? published < count : now - start < duration_ns;
    };
    if (rate <= 0) {
        while (more(bench::mono_ns())) publish_one();
    } else {
        constexpr std::int64_t batch_ns = 1000000;
        for (std::int64_t batch = 1;; ++batch) {
            const std::int64_t now = bench::mono_ns();
            if (!more(now)) break;
            auto due =
                static_cast<std::uint64_t>(static_cast<double>(batch) * batch_ns * rate / 1e9);
            if (count > 0) due = std::min(due, count);
            while (published < due) publish_one();
            const std::int64_t deadline = start + batch * batch_ns;
            if (bench::mono_ns() < deadline) bench::sleep_until_mono(deadline);
        }
    }
    const double elapsed = static_cast<double>(bench::mono_ns() - start) / 1e9;
    std::uint64_t completed = 0;
    std::uint64_t failed = 0;
    for (auto& window : windows) {
        std::unique_lock lock(window->mutex);
        window->done.wait_for(lock, std::chrono::seconds(30),
                              [&] { return window->outstanding == 0; });
    }
    const double drained = static_cast<double>(bench::mono_ns() - start) / 1e9;
    for (std::size_t c = 0; c < connections; ++c) {
        completed += windows[c]->completed.load();
        failed += windows[c]->failed.load();
        try {
            clients[c]->disconnect()->wait_for(std::chrono::seconds(5));
        } catch (const mqtt::exception&) {
        }
    }
    std::printf(
        "{\"published\":%llu,\"completed\":%llu,\"failed\":%llu,\"elapsed_s\":%.4f,"
        "\"drained_s\":%.4f,\"rate\":%.1f,\"window\":%zu,\"connections\":%zu}\n",
        static_cast<unsigned long long>(published), static_cast<unsigned long long>(completed),
        static_cast<unsigned long long>(failed), elapsed, drained,
        static_cast<double>(completed) / drained, window_size, connections);
    return 0;
}
