// The datagram router of a pair's standby: a datagram of an exchange this unit produces (the
// leader's, heard on a multicast group or broadcast both units receive) sets the request id its
// own producer sends next, while the standby follows; it is never counted as dropped. Without a
// pair such datagrams stay unknown ones. The producer is real, on a temporary state directory;
// the loop never runs.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/datagram_router.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::app {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using core::wire::DropReason;

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t rid) {
    return test::DatagramBuilder("10.0.0.1", exchange_id, 4).request_id(rid).build();
}

class DatagramRouterFollowedTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("eip2mqtt_router_followed_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        store_ = std::make_unique<adapters::state::ImageStore>(dir_.string());
        adapters::udp::SenderOptions sender_options;
        sender_options.bind = "127.0.0.1";
        sender_ = std::make_unique<adapters::udp::Sender>(loop_.get_executor(), sender_options);
        scheduler_ = std::make_unique<ProducerScheduler>(loop_.get_executor(), *sender_);
        persister_ =
            std::make_unique<adapters::state::ImagePersister>(*store_, loop_.get_executor());
        producers_.push_back(std::make_unique<ExchangeProducer>(
            test::test_produced_plan(), adapters::udp::Endpoint{0x7F000001, 9}, *scheduler_,
            *persister_, northbound_, totals_));
        persister_->flush();
    }
    void TearDown() override {
        producers_.clear();
        persister_.reset();
        scheduler_.reset();
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    void route(std::uint32_t exchange_id, std::uint16_t rid) {
        now_ += 10ms;
        router_.route(datagram(exchange_id, rid), {0x0A000002, 18246}, false, now_);
    }
    std::uint16_t next_id() const { return producers_.front()->image().next_request_id(); }

    fs::path dir_;
    boost::asio::io_context loop_;
    std::unique_ptr<adapters::state::ImageStore> store_;
    std::unique_ptr<adapters::udp::Sender> sender_;
    std::unique_ptr<ProducerScheduler> scheduler_;
    std::unique_ptr<adapters::state::ImagePersister> persister_;
    test::RecordingNorthbound northbound_;
    ImageSaveTotals totals_;
    std::vector<std::unique_ptr<ExchangeProducer>> producers_;
    DatagramRouter router_;
    core::MonoTime now_ = core::MonoTime{} + 1h;
};

TEST_F(DatagramRouterFollowedTest, AStandbyContinuesAfterTheLastRequestIdItHeard) {
    router_.set_followed(producers_, [](core::MonoTime) { return true; });
    route(10, 500);
    route(10, 501);
    EXPECT_EQ(next_id(), 502);
    // Wrapping, as the leader's ids do.
    route(10, 65535);
    EXPECT_EQ(next_id(), 0);
    EXPECT_EQ(router_.counters().produced_heard, 3u);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 0u);
    EXPECT_EQ(router_.counters().accepted, 0u);
    // Another exchange of the same producer id is no one's.
    route(11, 7);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 1u);
    EXPECT_EQ(next_id(), 0);
}

TEST_F(DatagramRouterFollowedTest, ALeaderHearingItsOwnDatagramsKeepsItsIds) {
    bool standing_by = false;
    router_.set_followed(producers_, [&](core::MonoTime) { return standing_by; });
    const auto own = next_id();
    route(10, 900);
    EXPECT_EQ(next_id(), own);
    EXPECT_EQ(router_.counters().produced_heard, 1u);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 0u);
    standing_by = true;
    route(10, 901);
    EXPECT_EQ(next_id(), 902);
}

TEST_F(DatagramRouterFollowedTest, WithoutAPairAProducedExchangeHeardIsUnknown) {
    router_.set_followed(producers_, nullptr);
    const auto own = next_id();
    route(10, 900);
    EXPECT_EQ(next_id(), own);
    EXPECT_EQ(router_.counters().produced_heard, 0u);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 1u);
}

}  // namespace
}  // namespace eip2mqtt::app
