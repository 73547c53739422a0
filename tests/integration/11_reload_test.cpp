// SIGHUP reloads: a valid change is applied without dropping the MQTT session or unchanged
// exchanges; an invalid file is refused and the old configuration keeps running. Every write
// accepted by a produced exchange that the reload changes or removes gets exactly one result:
// ok when a datagram carried it, else "reloaded".

#include <signal.h>
#include <sys/stat.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>
#include <vector>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

/// A consumed exchange of 10.0.0.1 with one tag at 0.0: A (dint) unless told otherwise.
ExchangeYaml exchange(const std::string& name, std::uint32_t id, const std::string& tag = "A",
                      const std::string& type = "dint") {
    return ExchangeYaml::consume(name, "10.0.0.1", id)
        .length(4)
        .period_ms(1000)
        .timeout_ms(0)
        .tag(tag, "0.0", type);
}

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t rid, std::int64_t v) {
    return DatagramBuilder("10.0.0.1", exchange_id, 4)
        .request_id(rid)
        .set("0.0", TagType::dint, v)
        .build();
}

/// A produced exchange with one writable dint VALUE at 0.0, sent to 127.0.0.1:`port`.
std::string produced(const std::string& name, std::uint32_t id, std::uint16_t port,
                     std::uint32_t period_ms, std::int64_t max = 1000000) {
    return ExchangeYaml::produce(name, "10.1.2.3", id, "127.0.0.1:" + std::to_string(port))
        .period_ms(period_ms)
        .tag("VALUE", "0.0", "dint", "writable: true, max: " + std::to_string(max))
        .str();
}

const json reloaded = {{"ok", false}, {"error", "reloaded"}};
const json ok = {{"ok", true}};

class ReloadTest : public GatewayTest {
protected:
    /// Publishes `payload` to `exchange`'s VALUE as an MQTT 5 request answered on
    /// replies/reload with correlation data `id`.
    void write(const std::string& exchange, const std::string& payload, const std::string& id) {
        recorder_->publish_request(topic(exchange + "/VALUE/set"), payload, replies_topic(), id);
    }
    /// A client's own topic: outside the base topic, where the gateway answers.
    std::string replies_topic() const { return "replies/reload"; }
    /// Every result received so far, by correlation data.
    std::map<std::string, std::vector<json>> replies() const {
        std::map<std::string, std::vector<json>> by_id;
        for (const auto& m : recorder_->messages_on(replies_topic())) {
            by_id[m.correlation_data].push_back(json::parse(m.payload));
        }
        return by_id;
    }
    /// Waits until every id of `ids` has a result (a second result of one write would show
    /// in the counts the tests check).
    bool wait_replies(const std::vector<std::string>& ids) {
        return recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                std::set<std::string> seen;
                for (const auto& m : all) {
                    if (m.topic == replies_topic()) seen.insert(m.correlation_data);
                }
                for (const auto& id : ids) {
                    if (!seen.contains(id)) return false;
                }
                return true;
            },
            10s);
    }
    std::size_t onlines() const {
        std::size_t n = 0;
        for (const auto& m : recorder_->messages_on(availability_topic()))
            n += m.payload == "online";
        return n;
    }
};

TEST_F(ReloadTest, ValidChangeIsAppliedWithoutDroppingTheSessionOrUnchangedExchanges) {
    start(exchange("kept", 1).str() + exchange("removed", 2).str() + exchange("changed", 3).str());
    send(datagram(1, 1, 11));
    send(datagram(2, 1, 22));
    send(datagram(3, 1, 33));
    expect_field(topic("kept/A"), "value", "11");
    expect_field(topic("removed/A"), "value", "22");
    expect_field(topic("changed/A"), "value", "33");
    const auto onlines_before = onlines();

    rewrite_exchanges(exchange("kept", 1).str() + exchange("changed", 3, "B", "int").str() +
                      exchange("added", 4).str());
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("1 exchange(s) kept, 2 started, 2 stopped (kept kept; "
                                      "changed changed; started added; stopped removed)"),
              std::string::npos)
        << gateway_->output();

    // The removed exchange's retained topics are cleared (an empty retained message).
    EXPECT_TRUE(recorder_->wait_for_message(topic("removed/A"),
                                            [](const std::string& p) { return p.empty(); }));
    EXPECT_TRUE(recorder_->wait_for_message(topic("changed/A"),
                                            [](const std::string& p) { return p.empty(); }));
    // The added and the changed exchange consume; the kept one never stopped (its sequence
    // goes on from request id 1: a restarted exchange would resynchronise and count nothing).
    send(datagram(4, 1, 44));
    expect_field(topic("added/A"), "value", "44");
    send(datagram(3, 5, 55));
    expect_field(topic("changed/B"), "value", "55");
    send(datagram(1, 3, 12));
    expect_field(topic("kept/A"), "value", "12");
    const auto status = recorder_->wait_for_message(
        topic("kept/_status"), [](const std::string& p) { return json::parse(p)["missed"] == 1; });
    EXPECT_TRUE(status.has_value()) << "kept exchange lost its sequence state";
    // Datagrams of the removed exchange are now unknown.
    send(datagram(2, 2, 23));
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        return json::parse(p)["dropped"]["unknown_exchange"] == 1;
    }));
    // The MQTT session was kept: no second `online`.
    EXPECT_EQ(onlines(), onlines_before);
}

TEST_F(ReloadTest, InvalidFileIsRefusedAndTheOldConfigurationKeepsRunning) {
    start(exchange("kept", 1).str());
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");

    rewrite_exchanges(exchange("kept", 1).key("colour", "blue").str());
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("reload refused", 10s)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("colour"), std::string::npos) << gateway_->output();
    send(datagram(1, 2, 12));
    expect_field(topic("kept/A"), "value", "12");
    EXPECT_TRUE(gateway_->running());
}

TEST_F(ReloadTest, APointListThatIsADirectoryOrAFifoIsRefusedAndTheOldConfigurationKeepsRunning) {
    // A directory made the reload die of std::bad_alloc (exit 1); a FIFO blocked the loop.
    start(exchange("kept", 1).str());
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");

    const auto directory = dir_.path() + "/dir.csv";
    std::filesystem::create_directory(directory);
    rewrite_exchanges(exchange("kept", 1).key("points", directory).str());
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output(
        "point list '" + directory + "' is not a regular file (a directory)", 10s))
        << gateway_->output();
    send(datagram(1, 2, 12));
    expect_field(topic("kept/A"), "value", "12");

    const auto fifo = dir_.path() + "/fifo.csv";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    rewrite_exchanges(exchange("kept", 1).key("points", fifo).str());
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(
        gateway_->wait_for_output("point list '" + fifo + "' is not a regular file (a FIFO)", 10s))
        << gateway_->output();
    send(datagram(1, 3, 13));
    expect_field(topic("kept/A"), "value", "13");

    EXPECT_TRUE(gateway_->running());
    const auto output = gateway_->output();
    std::size_t refusals = 0;
    for (auto at = output.find("reload refused"); at != std::string::npos;
         at = output.find("reload refused", at + 1)) {
        ++refusals;
    }
    EXPECT_EQ(refusals, 2u) << output;
}

TEST_F(ReloadTest, WritesQueuedOnAChangedOrRemovedExchangeAreAnsweredReloaded) {
    // An hour's period: after its first datagram (at start), no write to `sp` can be produced
    // before the reload; `gone`, second of two, first sends half an hour after start.
    UdpClient capture;
    start(produced("sp", 10, capture.port(), 3600000) +
          produced("gone", 11, capture.port(), 3600000));
    ASSERT_TRUE(capture.receive(5s).has_value());
    std::vector<std::string> ids;
    for (const std::string exchange : {"sp", "gone"}) {
        for (int i = 1; i <= 10; ++i) {
            ids.push_back(exchange + "-" + std::to_string(i));
            write(exchange, std::to_string(i), ids.back());
        }
        // A fence: a rejected write on the same topic, answered at once. Messages of one topic
        // reach the gateway in order, so once it is answered every write above is queued.
        write(exchange, "\"x\"", exchange + "-fence");
    }
    ASSERT_TRUE(wait_replies({"sp-fence", "gone-fence"}));
    EXPECT_TRUE(replies().at("sp-fence").at(0).value("error", "").find("string") !=
                std::string::npos)
        << replies().at("sp-fence").at(0).dump();

    // `sp` changes (its period), `gone` is removed.
    rewrite_exchanges(produced("sp", 10, capture.port(), 20));
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("0 exchange(s) kept, 1 started, 2 stopped"),
              std::string::npos)
        << gateway_->output();

    ASSERT_TRUE(wait_replies(ids)) << "writes left without a result";
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        return json::parse(p)["writes_cancelled"] == 20;
    }));
    // None of them reached the restarted exchange's image.
    const auto next = capture.receive(5s);
    ASSERT_TRUE(next.has_value());
    EXPECT_EQ(core::plan::decode_value(std::span(*next).subspan(32), TagType::dint, {0, 0}),
              core::plan::Value{std::int64_t{0}});
    // The restarted exchange takes writes again. Its result comes after any the reload
    // published (one connection, one topic: in order), so the counts below are final.
    write("sp", "42", "sp-after");
    ASSERT_TRUE(wait_replies({"sp-after"}));
    const auto all = replies();
    EXPECT_EQ(all.at("sp-after"), std::vector<json>{ok});
    // Every queued write got exactly one result, "reloaded", with its correlation data.
    for (const auto& id : ids) {
        ASSERT_EQ(all.at(id).size(), 1u) << id;
        EXPECT_EQ(all.at(id)[0], reloaded) << id;
    }
}

TEST_F(ReloadTest, EveryWriteDuringAReloadGetsExactlyOneResult) {
    // Writes stream to an exchange produced every 20 ms while a reload restarts it: whichever
    // side of the swap each lands on, it is answered once, ok or "reloaded", never left silent.
    UdpClient capture;
    start(produced("sp", 10, capture.port(), 20));
    ASSERT_TRUE(capture.receive(5s).has_value());
    rewrite_exchanges(produced("sp", 10, capture.port(), 20, 999999));
    std::vector<std::string> ids;
    for (int i = 1; i <= 300; ++i) {
        ids.push_back("w" + std::to_string(i));
        write("sp", std::to_string(i), ids.back());
        if (i == 100) gateway_->signal(SIGHUP);
    }
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    ASSERT_TRUE(wait_replies(ids)) << "writes left without a result";
    // A last write's result comes after every other (in order on one topic): counts are final.
    write("sp", "1", "last");
    ASSERT_TRUE(wait_replies({"last"}));
    const auto all = replies();
    EXPECT_EQ(all.at("last"), std::vector<json>{ok});
    std::size_t oks = 0;
    for (const auto& id : ids) {
        ASSERT_EQ(all.at(id).size(), 1u) << id;
        const auto& result = all.at(id)[0];
        EXPECT_TRUE(result == ok || result == reloaded) << id << ": " << result.dump();
        oks += result == ok;
    }
    // Those answered "reloaded" are the gateway's count of cancelled writes.
    const auto cancelled = ids.size() - oks;
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(),
                                            [&](const std::string& p) {
                                                const auto m = json::parse(p);
                                                return m["writes_ok"] == ids.size() + 1 &&
                                                       m["writes_cancelled"] == cancelled;
                                            }))
        << cancelled << " cancelled";
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
