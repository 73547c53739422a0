#pragma once
/// The store-and-forward integration tests' set-up
/// (tests/integration/41_store_and_forward_test.cpp): a counter sent at 100 datagrams a second, a
/// gateway that journals while the broker is out, and what a subscriber of `_values` and `_history`
/// together received.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/gateway_fixture.hpp"
#include "tests/support/paced_producer.hpp"

namespace eip2mqtt::test {

class StoreAndForwardTest : public GatewayTest {
protected:
    /// Starts broker, gateway (consuming `line`, batch on, with these `store_and_forward` keys)
    /// and the counter; with `prometheus`, the metrics endpoint on prometheus_port_.
    void start_gateway_with(const std::string& store_and_forward, bool prometheus = false,
                            const std::string& sections = "");
    /// The same with `options` as they are, and `before_counter` run once the gateway started
    /// and before the counter sends its first datagram (a recorder of the test's own, say).
    void start_gateway_with(const std::string& store_and_forward, GatewayOptions options,
                            const std::string& mqtt_extra,
                            const std::function<void()>& before_counter);

    /// The publications on `_values` (live) or `_history` as the gateway made them, in
    /// arrival order. When the broker restarts, it sends the recorder's unacknowledged
    /// deliveries again with DUP set (QoS 1 between the broker and us): a repeat of a payload
    /// already received is not the gateway's doing and is left out. A DUP delivery whose
    /// first copy never arrived (the broker wrote it as it stopped) is the delivery, and counts.
    std::vector<const Received*> deliveries_on(const std::string& suffix,
                                               const std::vector<Received>& all) const;
    /// The same rule for any topic, kept from the `from`th message on (the repeats are known
    /// from all of them).
    static std::vector<const Received*> deliveries(const std::string& wanted,
                                                   const std::vector<Received>& all,
                                                   std::size_t from);
    static std::uint64_t counter_of(const Received& m);

    /// COUNTER values of deliveries_on(suffix), in arrival order.
    std::vector<std::uint64_t> values_on(const std::string& suffix) const;
    /// The same within `all` (what a wait_for predicate is given: the recorder is locked).
    std::vector<std::uint64_t> values_on(const std::string& suffix,
                                         const std::vector<Received>& all) const;

    /// Waits until live and history together hold every value 1..last.
    bool wait_all_received(std::uint64_t last,
                           std::chrono::seconds timeout = std::chrono::seconds(60));

    /// Every value 1..last once over both topics, each topic in increasing order. One
    /// exception, QoS 1's own: a publication in flight when a connection drops is sent again
    /// after the reconnect, and the broker may have taken it before it went. Such a repeat is
    /// the same message again (same topic, same payload: a historian keeps it once), at most a
    /// few per outage (`outages`). It may come before or after its place in the order (a
    /// restarted broker first sends what it kept), so the order asked for is that of one delivery
    /// of each value.
    void expect_each_value_once(std::uint64_t last, int outages = 1);
    /// The same of what `recorder` received under `base` (another connection's broker).
    void expect_each_value_once(MqttRecorder& recorder, const std::string& base, std::uint64_t last,
                                int outages = 1);

    /// Pauses the counter once live `_values` delivered its last value: nothing is queued.
    std::uint64_t pause_when_delivered();

    /// Starts the broker again, waits until the gateway is online and live `_values` carry a
    /// value sent after that, then pauses the counter; returns its last value.
    std::uint64_t end_outage_once_live_again();

    /// Stops the broker, once the gateway has said it lost the connection.
    void stop_broker();

    /// How many times the gateway's output holds `text`.
    std::size_t count_output(const std::string& text) const;
    /// Bounded polling of the gateway's log, which has no event of its own.
    bool wait_output_count(const std::string& text, std::size_t count) const;

    /// A figure of the Prometheus page; nullopt when absent.
    std::optional<double> metric(const std::string& name) const;
    /// Polls the Prometheus page (bounded) until `name` satisfies `pred`.
    bool wait_metric(const std::string& name, const std::function<bool(double)>& pred,
                     std::chrono::seconds timeout = std::chrono::seconds(20)) const;

    /// Sends the `line` exchange every 10 ms, COUNTER counting up from 1.
    std::unique_ptr<PacedProducer> counter_;
    std::uint16_t prometheus_port_ = 0;
};

}  // namespace eip2mqtt::test
