// `sniff` without a capture: the line it prints for each datagram (receive time, source, header,
// the configured tags), the sequence of each exchange (duplicates, misses, reordering, the
// resynchronisation after a silence), the statistics table and the load line over the time its
// clock says, the --yaml skeleton of what the configuration lacks, the set-up it takes from its
// options, and run_sniff's refusals. Times come from a FakeClock, printed in UTC.

#include <gtest/gtest.h>
#include <time.h>

#include <chrono>
#include <cstdlib>
#include <sstream>
#include <string>

#include "app/cli/detail/sniffer.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;

/// Exchange `line` (producer 10.0.0.1, exchange 7): 100 ms period, resynchronised after 300 ms
/// of silence, SPEED a dint at byte 0 and FLOW at byte 8, past the 4 bytes the tests send.
const char* configuration =
    "mqtt:\n  url: tcp://a:1883\neip:\n  port: 18300\nexchanges:\n"
    "  - { name: line, producer_id: 10.0.0.1, exchange_id: 7, length: 12, period_ms: 100,\n"
    "      timeout_ms: 300, tags: [ { name: SPEED, address: \"0.0\", type: dint },\n"
    "                               { name: FLOW, address: \"8.0\", type: dint } ] }\n";

std::vector<std::byte> datagram(const char* producer, std::uint32_t exchange, std::uint16_t rid,
                                std::int64_t speed = 0) {
    return test::DatagramBuilder(producer, exchange, 4)
        .request_id(rid)
        .set("0.0", TagType::dint, core::plan::Value{speed})
        .build();
}

/// The lines of `text`.
std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

class SniffTest : public ::testing::Test {
protected:
    SniffTest() {
        ::setenv("TZ", "UTC", 1);
        ::tzset();
    }

    /// A sniffer of `plans`, its tables every second.
    Sniffer& sniffer(std::vector<core::plan::ExchangePlan> plans = {}, bool yaml = false) {
        std::optional<YamlSettings> settings;
        if (yaml) settings.emplace();
        sniffer_.emplace(out_, std::move(plans), 1s, std::move(settings), clock_);
        return *sniffer_;
    }
    std::vector<core::plan::ExchangePlan> configured() {
        SniffOptions options;
        options.config_path = dir_.write("gw.yaml", configuration);
        std::ostringstream err;
        auto setup = load_setup(options, err);
        EXPECT_TRUE(setup.has_value()) << err.str();
        return std::move(setup->plans);
    }
    void hear(const std::vector<std::byte>& bytes) {
        sniffer_->on_datagram(bytes, {0x0A000001, 2222}, 0xEFC00001);
    }
    /// What was printed since the last call.
    std::string printed() {
        auto text = out_.str();
        out_.str("");
        return text;
    }

    test::TempDir dir_;
    test::FakeClock clock_;  // 2026-01-01T00:00:00Z
    std::ostringstream out_;
    std::optional<Sniffer> sniffer_;
};

TEST_F(SniffTest, EachDatagramIsALineWithItsReceiveTimeSourceAndHeader) {
    sniffer();
    clock_.advance(1500ms);
    test::DatagramBuilder builder("10.0.0.2", 9, 4);
    builder.request_id(5).header().status = 1;
    hear(builder.build());
    EXPECT_EQ(printed(),
              "00:00:01.500000 10.0.0.1:2222 rid=5 producer=10.0.0.2 exchange=9 time=none "
              "status=1 signature=0.0 length=4\n");
}

TEST_F(SniffTest, TheProducersTimeIsPrintedInUtcToTheNanosecond) {
    core::wire::Header header;
    EXPECT_EQ(producer_time(header), "none");
    header.time_s = 1767225600;
    header.time_ns = 5;
    EXPECT_EQ(producer_time(header), "2026-01-01T00:00:00.000000005Z");
    EXPECT_EQ(local_time(clock_.wall() + 61s + 250us), "00:01:01.000250");
}

TEST_F(SniffTest, AConfiguredExchangeIsNamedAndItsTagsDecodedThoseBeyondTheDataUnknown) {
    sniffer(configured());
    hear(datagram("10.0.0.1", 7, 1, -42));
    EXPECT_TRUE(contains(printed(), " length=4 [line] SPEED=-42 FLOW=?\n"));
}

TEST_F(SniffTest, DuplicatesMissesAndReorderingAreSaidAndCountedInTheTable) {
    sniffer();
    for (const std::uint16_t rid : {1, 1, 4, 3, 5}) {
        hear(datagram("10.0.0.2", 9, rid));
        clock_.advance(100ms);
    }
    const auto heard = lines(printed());
    ASSERT_EQ(heard.size(), 5u);
    EXPECT_FALSE(contains(heard[0], "duplicate"));
    EXPECT_TRUE(contains(heard[1], " duplicate"));
    EXPECT_TRUE(contains(heard[3], " out_of_order"));
    sniffer_->print_statistics(0, 0);
    const auto table = lines(printed());
    ASSERT_EQ(table.size(), 3u);
    EXPECT_EQ(table[0], "-- statistics at 00:00:00.500000 --");
    // Three samples (rids 1, 4, 5) 200 ms apart, all within the last second; without a
    // configured period, the reference of the jitter is the mean: none.
    EXPECT_EQ(table[2],
              "10.0.0.2/9         5       3.0    200.000      0.000        2          1         "
              "   1");
}

TEST_F(SniffTest, TheRateCountsTheArrivalsOfTheLastIntervalByTheClock) {
    sniffer();
    for (std::uint16_t rid = 1; rid <= 10; ++rid) {
        hear(datagram("10.0.0.2", 9, rid));
        clock_.advance(100ms);
    }
    clock_.advance(400ms);  // the last second, (0.4 s, 1.4 s], holds the last five
    sniffer_->print_statistics(0, 0);
    EXPECT_TRUE(contains(printed(), "10.0.0.2/9        10       5.0    100.000      0.000"));
}

TEST_F(SniffTest, AConfiguredExchangeResynchronisesAfterASilenceLongerThanItsTimeout) {
    sniffer(configured());
    hear(datagram("10.0.0.1", 7, 1));
    clock_.advance(200ms);
    hear(datagram("10.0.0.1", 7, 3));  // one missed
    clock_.advance(301ms);
    hear(datagram("10.0.0.1", 7, 50));  // after the timeout: no miss counted
    sniffer_->print_statistics(0, 0);
    const auto table = lines(printed());
    ASSERT_GE(table.size(), 4u);
    EXPECT_TRUE(contains(table[5], "line             3")) << table[5];
    EXPECT_TRUE(contains(table[5], "        1          0            0")) << table[5];
}

TEST_F(SniffTest, TheLoadIsMeasuredOverTheClocksTimeSinceTheLastTable) {
    sniffer(configured());
    printed();
    for (std::uint16_t rid = 1; rid <= 4; ++rid) hear(datagram("10.0.0.1", 7, rid));
    clock_.advance(2s);
    sniffer_->print_statistics(0, 0);
    const auto bytes = core::plan::wire_bytes_of_datagram(core::wire::header_size + 4);
    EXPECT_TRUE(contains(printed(), "load: measured 2 datagrams/s, " +
                                        std::to_string(bytes * 4 * 8 / 2) + " bit/s (4 datagrams"));
    clock_.advance(1s);  // a new window, and nothing in it
    sniffer_->print_statistics(0, 0);
    EXPECT_TRUE(contains(printed(), "load: measured 0 datagrams/s, 0 bit/s (4 datagrams"));
}

TEST_F(SniffTest, MalformedDatagramsFragmentsAndCaptureDropsAreCounted) {
    sniffer();
    sniffer_->print_statistics(0, 0);
    EXPECT_EQ(printed(), "");  // nothing heard: no table
    hear(std::vector<std::byte>(3));
    EXPECT_EQ(printed(), "00:00:00.000000 10.0.0.1:2222 dropped=too_short length=3\n");
    sniffer_->print_statistics(2, 5);
    const auto table = printed();
    EXPECT_TRUE(contains(table, "dropped: too_short=1\n"));
    EXPECT_TRUE(contains(table, "ip fragments: 2 (not decoded"));
    EXPECT_TRUE(contains(table, "capture dropped: 5 (sniff could not keep up)\n"));
}

TEST_F(SniffTest, WithYamlTheSkeletonHoldsTheExchangesTheConfigurationLacks) {
    sniffer(configured(), true);
    hear(datagram("10.0.0.1", 7, 1));
    hear(datagram("10.0.0.2", 9, 1));
    clock_.advance(100ms);
    hear(datagram("10.0.0.2", 9, 2));
    printed();
    sniffer_->print_skeleton();
    const auto skeleton = printed();
    EXPECT_TRUE(contains(skeleton, "exchange_id: 9")) << skeleton;
    EXPECT_TRUE(contains(skeleton, "10.0.0.2")) << skeleton;
    EXPECT_FALSE(contains(skeleton, "exchange_id: 7")) << skeleton;
}

TEST_F(SniffTest, ThePortIsTheOptionsElseTheConfigurationsElse18246) {
    SniffOptions options;
    std::ostringstream err;
    EXPECT_EQ(load_setup(options, err)->port, 18246);
    options.config_path = dir_.write("gw.yaml", configuration);
    const auto setup = load_setup(options, err);
    EXPECT_EQ(setup->port, 18300);
    EXPECT_EQ(setup->plans.size(), 1u);
    EXPECT_FALSE(setup->yaml.has_value());
    options.port = 18400;
    options.yaml = true;
    EXPECT_EQ(load_setup(options, err)->port, 18400);
    EXPECT_TRUE(load_setup(options, err)->yaml.has_value());
}

TEST_F(SniffTest, AConfigurationWithErrorsIsRefusedWithThem) {
    SniffOptions options;
    options.config_path = dir_.write("bad.yaml", "mqtt:\n  url: tcp://a:1883\nexchanges: 3\n");
    std::ostringstream err;
    EXPECT_FALSE(load_setup(options, err).has_value());
    EXPECT_TRUE(contains(err.str(), "bad.yaml:3:")) << err.str();
    std::ostringstream out;
    EXPECT_EQ(run_sniff(options, out), 1);
}

TEST_F(SniffTest, RunSniffRefusesAnIntervalThatIsNotPositiveAndABindThatIsNoAddress) {
    SniffOptions options;
    options.interval_s = 0;
    std::ostringstream out;
    EXPECT_EQ(run_sniff(options, out), 2);
    options.interval_s = 1;
    options.bind = "not-an-address";
    EXPECT_EQ(run_sniff(options, out), 1);
    EXPECT_EQ(out.str(), "");  // never started
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
