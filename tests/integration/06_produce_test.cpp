// Produced exchanges: exact headers and data on the wire, request ids, the period, and the
// image surviving a restart.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using namespace std::chrono_literals;

std::string produced_exchange(std::uint16_t port, int period_ms) {
    return ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(port))
        .key("signature", "\"3.7\"")
        .period_ms(period_ms)
        .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000, initial: 3000")
        .tag("START", "4.0", "bit", "writable: true")
        .tag("STOP", "4.3", "bit", "writable: true, initial: true")
        .tag("MODE", "5.0", "byte", "writable: true, initial: 7")
        .tag("OFFSET", "6.0", "int", "writable: true, initial: -5")
        .tag("COUNT", "8.0", "word", "writable: true, initial: 65535")
        .tag("FLOW", "10.0", "dint", "writable: true, initial: -100000")
        .tag("ENERGY", "14.0", "udint", "writable: true, initial: 3000000000")
        .tag("TOTAL", "18.0", "lint", "writable: true, initial: -2")
        .tag("GAIN", "26.0", "lreal", "writable: true, initial: 1.25")
        .tag("LIMIT", "34.0", "word", "initial: 100")
        .str();
}

core::wire::Datagram decode(const std::vector<std::byte>& bytes) {
    auto decoded = core::wire::decode_datagram(bytes);
    EXPECT_TRUE(decoded.ok());
    return decoded.value();
}

Value tag(const std::vector<std::byte>& bytes, const char* address, TagType type) {
    return core::plan::decode_value(std::span(bytes).subspan(32), type,
                                    core::plan::parse_address(address).value());
}

class ProduceTest : public GatewayTest {};

TEST_F(ProduceTest, HeaderAndDataOfEveryTypeAreExact) {
    UdpClient capture;
    start(produced_exchange(capture.port(), 50));
    const auto bytes = capture.receive(5s);
    ASSERT_TRUE(bytes.has_value());
    ASSERT_EQ(bytes->size(), 32u + 36u);
    const auto datagram = decode(*bytes);
    const auto& h = datagram.header;
    EXPECT_EQ(h.pdu_type, 0x0D);
    EXPECT_EQ(h.pdu_version, 1);
    EXPECT_EQ(core::wire::to_string(h.producer_id), "10.1.2.3");
    EXPECT_EQ((*bytes)[4], std::byte{10});  // dotted order on the wire
    EXPECT_EQ(h.exchange_id, 10u);
    EXPECT_EQ(h.status, 0u);
    EXPECT_EQ(h.reserved, 0u);
    EXPECT_EQ((*bytes)[25], std::byte{3});  // signature major
    EXPECT_EQ((*bytes)[24], std::byte{7});  // signature minor
    const auto now_s = std::chrono::duration_cast<std::chrono::seconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
    EXPECT_NEAR(static_cast<double>(h.time_s), static_cast<double>(now_s), 5.0);
    EXPECT_LT(h.time_ns, 1000000000u);

    EXPECT_EQ(tag(*bytes, "0.0", TagType::real), Value{3000.0f});
    EXPECT_EQ(tag(*bytes, "4.0", TagType::bit), Value{false});
    EXPECT_EQ(tag(*bytes, "4.3", TagType::bit), Value{true});
    EXPECT_EQ((*bytes)[32 + 4], std::byte{0x08});  // only bit 3 of byte 4
    EXPECT_EQ(tag(*bytes, "5.0", TagType::byte), Value{std::uint64_t{7}});
    EXPECT_EQ(tag(*bytes, "6.0", TagType::int_), Value{std::int64_t{-5}});
    EXPECT_EQ(tag(*bytes, "8.0", TagType::word), Value{std::uint64_t{65535}});
    EXPECT_EQ(tag(*bytes, "10.0", TagType::dint), Value{std::int64_t{-100000}});
    EXPECT_EQ(tag(*bytes, "14.0", TagType::udint), Value{std::uint64_t{3000000000}});
    EXPECT_EQ(tag(*bytes, "18.0", TagType::lint), Value{std::int64_t{-2}});
    EXPECT_EQ(tag(*bytes, "26.0", TagType::lreal), Value{1.25});
    EXPECT_EQ(tag(*bytes, "34.0", TagType::word), Value{std::uint64_t{100}});
}

// What load cannot change: every datagram takes the next request id, and carries the time of
// the deadline it serves, so each step is a whole number of periods; a step of more than one
// is a deadline the gateway skipped because it fell behind, and is counted in `_status`. How
// close to its deadline each datagram left is measured by the benchmark (scenario 7).
TEST_F(ProduceTest, RequestIdsFollowEachOtherAndTimestampsStepByWholePeriods) {
    UdpClient capture;
    constexpr std::int64_t period_ns = 10'000'000;
    start(produced_exchange(capture.port(), 10));
    constexpr int count = 300;
    std::vector<core::wire::Header> headers;
    while (headers.size() < count) {
        const auto bytes = capture.receive(5s);
        ASSERT_TRUE(bytes.has_value()) << "after " << headers.size() << " datagrams";
        headers.push_back(decode(*bytes).header);
    }
    auto ns = [](const core::wire::Header& h) {
        return static_cast<std::int64_t>(h.time_s) * 1'000'000'000 +
               static_cast<std::int64_t>(h.time_ns);
    };
    std::int64_t skipped = 0;
    for (std::size_t i = 1; i < headers.size(); ++i) {
        ASSERT_EQ(static_cast<std::uint16_t>(headers[i - 1].request_id + 1), headers[i].request_id)
            << "at " << i;
        const auto step = ns(headers[i]) - ns(headers[i - 1]);
        ASSERT_GT(step, 0) << "at " << i;
        ASSERT_EQ(step % period_ns, 0) << "a step of " << step << " ns at " << i;
        skipped += step / period_ns - 1;
    }
    // The counter covers at least the skips seen here (it goes on counting meanwhile).
    const auto status = recorder_->wait_for_message(topic("sp/_status"), [&](const std::string& p) {
        const auto json = nlohmann::json::parse(p, nullptr, false);
        return json.contains("skipped_deadlines") && json.contains("request_id") &&
               json["skipped_deadlines"].get<std::int64_t>() >= skipped;
    });
    EXPECT_TRUE(status.has_value()) << skipped << " skipped deadlines seen on the wire";
}

TEST_F(ProduceTest, EchoTopicsCarryTheProducedValues) {
    UdpClient capture;
    start(produced_exchange(capture.port(), 50));
    expect_field(topic("sp/SPEED_SP"), "value", "3000.0");
    expect_field(topic("sp/STOP"), "value", "true");
    expect_field(topic("sp/_status"), "state", "\"producing\"");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
