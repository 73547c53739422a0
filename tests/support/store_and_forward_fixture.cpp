#include "tests/support/store_and_forward_fixture.hpp"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/prometheus_page.hpp"

namespace eip2mqtt::test {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

namespace {

/// The `line` exchange's datagram `n`: COUNTER is n.
std::vector<std::byte> counter_datagram(std::uint64_t n) {
    return DatagramBuilder("10.0.0.2", 7, 4)
        .request_id(static_cast<std::uint16_t>(n))
        .set("0.0", TagType::udint, std::uint64_t{n})
        .build();
}

/// Whether one delivery of each value can be picked so that the picks come in increasing order:
/// the gateway's own order, once QoS 1's repeats are set aside. A repeat may come before the
/// value's place as well as after it: a restarted broker first sends what it kept from before its
/// stop (some of the values in flight), then the gateway sends all of them again, in order.
bool in_order_but_for_repeats(const std::vector<std::uint64_t>& arrivals) {
    std::map<std::uint64_t, std::vector<std::size_t>> positions;  // each value's arrivals, in turn
    for (std::size_t i = 0; i < arrivals.size(); ++i) positions[arrivals[i]].push_back(i);
    std::optional<std::size_t> previous;
    for (const auto& [value, at] : positions) {
        // The earliest arrival after the previous pick leaves the most room for the rest.
        const auto pick = std::find_if(at.begin(), at.end(),
                                       [&](std::size_t i) { return !previous || i > *previous; });
        if (pick == at.end()) return false;
        previous = *pick;
    }
    return true;
}

}  // namespace

void StoreAndForwardTest::start_gateway_with(const std::string& store_and_forward, bool prometheus,
                                             const std::string& sections) {
    GatewayOptions options;
    options.sections = sections;
    options.broker.persistence = true;  // the recorder's session survives the outage
    // Everything published before the recorder is back is kept for it (Mosquitto's
    // default keeps 1,000 messages per offline session and drops the rest).
    options.broker.extra_config = "max_queued_messages 0\n";
    if (prometheus) {
        prometheus_port_ = free_tcp_port();
        options.sections +=
            "metrics:\n  listen: 127.0.0.1:" + std::to_string(prometheus_port_) + "\n";
    }
    start_gateway_with(store_and_forward, std::move(options), "", nullptr);
}

void StoreAndForwardTest::start_gateway_with(const std::string& store_and_forward,
                                             GatewayOptions options, const std::string& mqtt_extra,
                                             const std::function<void()>& before_counter) {
    start(ExchangeYaml::consume("line", "10.0.0.2", 7)
              .length(4)
              .period_ms(10)
              .timeout_ms(0)
              .tag("COUNTER", "0.0", "udint")
              .str(),
          "  batch: true\n" + mqtt_extra + "  store_and_forward:\n" + store_and_forward,
          std::move(options));
    if (before_counter) before_counter();
    counter_ = std::make_unique<PacedProducer>(
        counter_datagram, [this](const auto& d) { send(d); }, 10ms);
}

std::vector<const Received*> StoreAndForwardTest::deliveries_on(
    const std::string& suffix, const std::vector<Received>& all) const {
    return deliveries(topic("line/" + suffix), all, 0);
}

std::vector<const Received*> StoreAndForwardTest::deliveries(const std::string& wanted,
                                                             const std::vector<Received>& all,
                                                             std::size_t from) {
    std::vector<const Received*> out;
    std::set<std::string_view> payloads;
    for (std::size_t i = 0; i < all.size(); ++i) {
        const auto& m = all[i];
        if (m.topic != wanted) continue;
        const bool repeat = !payloads.insert(m.payload).second;
        if ((m.duplicate && repeat) || i < from) continue;
        out.push_back(&m);
    }
    return out;
}

std::uint64_t StoreAndForwardTest::counter_of(const Received& m) {
    return json::parse(m.payload)["values"]["COUNTER"].get<std::uint64_t>();
}

std::vector<std::uint64_t> StoreAndForwardTest::values_on(const std::string& suffix) const {
    return values_on(suffix, recorder_->messages());
}

std::vector<std::uint64_t> StoreAndForwardTest::values_on(const std::string& suffix,
                                                          const std::vector<Received>& all) const {
    std::vector<std::uint64_t> values;
    for (const auto* m : deliveries_on(suffix, all)) values.push_back(counter_of(*m));
    return values;
}

bool StoreAndForwardTest::wait_all_received(std::uint64_t last, std::chrono::seconds timeout) {
    return recorder_->wait_for(
        [&](const std::vector<Received>& all) {
            std::set<std::uint64_t> seen;
            for (const auto* suffix : {"_values", "_history"}) {
                for (const auto v : values_on(suffix, all)) seen.insert(v);
            }
            return seen.size() >= last && seen.contains(1) && seen.contains(last);
        },
        timeout);
}

void StoreAndForwardTest::expect_each_value_once(std::uint64_t last, int outages) {
    expect_each_value_once(*recorder_, base_topic, last, outages);
}

void StoreAndForwardTest::expect_each_value_once(MqttRecorder& recorder, const std::string& base,
                                                 std::uint64_t last, int outages) {
    std::map<std::uint64_t, int> count;
    std::map<std::uint64_t, std::set<std::string>> payloads;
    bool unsorted = false;
    const auto all = recorder.messages();
    const auto line = [&base](const char* suffix) { return base + "/line/" + suffix; };
    for (const auto* suffix : {"_values", "_history"}) {
        std::vector<std::uint64_t> arrivals;
        for (const auto* m : deliveries(line(suffix), all, 0)) {
            const auto v = counter_of(*m);
            ++count[v];
            payloads[v].insert(suffix + m->payload);
            arrivals.push_back(v);
        }
        const bool sorted = in_order_but_for_repeats(arrivals);
        EXPECT_TRUE(sorted) << suffix << " out of order";
        unsorted = unsorted || !sorted;
    }
    std::vector<std::uint64_t> missing;
    std::vector<std::uint64_t> twice;
    for (std::uint64_t v = 1; v <= last; ++v) {
        if (count[v] == 0) missing.push_back(v);
        if (count[v] > 1) twice.push_back(v);
        EXPECT_LE(payloads[v].size(), 1u) << "value " << v << " came twice, differently";
    }
    EXPECT_TRUE(missing.empty()) << missing.size() << " values missing, first "
                                 << (missing.empty() ? 0 : missing.front());
    EXPECT_LE(twice.size(), 5u * static_cast<std::size_t>(outages))
        << twice.size() << " values repeated, first " << (twice.empty() ? 0 : twice.front());
    EXPECT_EQ(count.rbegin()->first, last);
    if (unsorted || !missing.empty() || twice.size() > 5u * static_cast<std::size_t>(outages)) {
        for (const auto* suffix : {"_values", "_history"}) {
            std::ostringstream ranges;  // runs of consecutive values, to see what is where
            std::vector<std::uint64_t> values;
            for (const auto* m : deliveries(line(suffix), all, 0)) values.push_back(counter_of(*m));
            for (std::size_t i = 0; i < values.size(); ++i) {
                if (i == 0 || values[i] != values[i - 1] + 1) {
                    ranges << (i ? "-" + std::to_string(values[i - 1]) + " " : "") << values[i];
                }
            }
            if (!values.empty()) ranges << "-" << values.back();
            std::ostringstream repeated;  // every delivery flagged DUP, counted or not
            const auto wanted = line(suffix);
            for (const auto& m : all) {
                if (m.duplicate && m.topic == wanted) {
                    repeated << " " << counter_of(m);
                }
            }
            ADD_FAILURE() << suffix << ": " << ranges.str() << "; DUP:" << repeated.str();
        }
    }
}

std::uint64_t StoreAndForwardTest::pause_when_delivered() {
    const auto last = counter_->pause();
    EXPECT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) {
            const auto live = values_on("_values", all);
            return !live.empty() && live.back() == last;
        },
        10s));
    return last;
}

std::uint64_t StoreAndForwardTest::end_outage_once_live_again() {
    const auto from = recorder_->count();
    broker_->start();
    wait_online(from);
    const auto at_online = counter_->last();
    EXPECT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) {
            const auto live = values_on("_values", all);
            return !live.empty() && live.back() > at_online;
        },
        10s));
    return counter_->pause();
}

void StoreAndForwardTest::stop_broker() {
    const auto losses = count_output(" lost: ");
    broker_->stop();
    ASSERT_TRUE(wait_output_count(" lost: ", losses + 1)) << gateway_->output();
}

std::size_t StoreAndForwardTest::count_output(const std::string& text) const {
    const auto output = gateway_->output();
    std::size_t count = 0;
    for (auto at = output.find(text); at != std::string::npos; at = output.find(text, at + 1)) {
        ++count;
    }
    return count;
}

bool StoreAndForwardTest::wait_output_count(const std::string& text, std::size_t count) const {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (count_output(text) < count) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(20ms);
    }
    return true;
}

std::optional<double> StoreAndForwardTest::metric(const std::string& name) const {
    return prometheus_figure(prometheus_port_, name);
}

bool StoreAndForwardTest::wait_metric(const std::string& name,
                                      const std::function<bool(double)>& pred,
                                      std::chrono::seconds timeout) const {
    return wait_prometheus_figure(prometheus_port_, name, pred, timeout);
}

}  // namespace eip2mqtt::test
