// A pair's produced images at run time, against a recording publisher and a real producer on a
// temporary state directory: what the leader publishes, and what the standby takes into its
// producer (and saves) or ignores. The rules themselves are tested in
// tests/core/redundancy/image_follow_test.cpp. The loop never runs: saves are flushed by hand.

#include "eip2mqtt/app/redundancy/pair_images.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <filesystem>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/redundancy/image_message.hpp"
#include "tests/app/support/producer_rig.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/log_capture.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::app::redundancy {
namespace {

namespace fs = std::filesystem;
using core::redundancy::FollowVerdict;
using core::redundancy::ImageMessage;

const std::string prefix = "acme/_gateway/_pair/turbine/image";
const std::string topic = prefix + "/site/sp";

core::plan::ExchangePlan make_plan(std::uint16_t length = 4) {
    return test::test_produced_plan("site/sp", length);
}

std::vector<std::byte> bytes(std::initializer_list<int> values) {
    std::vector<std::byte> out;
    for (const int v : values) out.push_back(static_cast<std::byte>(v));
    return out;
}

class PairImagesTest : public ::testing::Test {
protected:
    void SetUp() override { producers_.push_back(rig_.make(make_plan(), northbound_)); }
    void TearDown() override { producers_.clear(); }

    ExchangeProducer& producer() { return *producers_.front(); }
    std::uint64_t layout() const { return adapters::state::layout_fingerprint(make_plan()); }
    std::vector<std::byte> image() {
        return {producer().image().data().begin(), producer().image().data().end()};
    }
    adapters::mqtt::Incoming incoming(const ImageMessage& image, const std::string& on = topic) {
        return {on, encode_image_message(image)};
    }
    std::optional<FollowVerdict> read(const ImageMessage& image, bool leading = false,
                                      std::uint64_t epoch = 3) {
        return images_.on_message(incoming(image), producers_, leading, epoch);
    }

    test::ProducerRig rig_{"eip2mqtt_pair_images"};
    test::RecordingNorthbound northbound_;
    std::vector<std::unique_ptr<ExchangeProducer>> producers_;
    test::RecordingPublisher publisher_;
    PairImages images_{prefix, "gw-b", publisher_};
};

TEST_F(PairImagesTest, TheTopicOfAnExchangeIsItsTopicUnderThePairs) {
    EXPECT_EQ(images_.topic_of(producer().plan()), topic);
    EXPECT_TRUE(images_.owns(topic));
    EXPECT_FALSE(images_.owns(prefix));
    EXPECT_FALSE(images_.owns(prefix + "/"));
    EXPECT_FALSE(images_.owns(prefix + "s/sp"));
    EXPECT_FALSE(images_.owns("acme/_gateway/_pair/turbine/leader"));
}

TEST_F(PairImagesTest, TheLeaderPublishesItsImageRetainedWithItsEpochAndLayout) {
    images_.publish(producer(), 7);
    ASSERT_EQ(publisher_.published.size(), 1u);
    const auto& message = publisher_.published.front();
    EXPECT_EQ(message.topic, topic);
    EXPECT_EQ(message.qos, 1);
    EXPECT_TRUE(message.retain);
    EXPECT_EQ(decode_image_message(message.payload), (ImageMessage{"gw-b", 7, layout(), image()}));
    EXPECT_EQ(images_.counters().published, 1u);
}

TEST_F(PairImagesTest, TheStandbyTakesTheLeadersImageAndSavesIt) {
    const auto written = bytes({0x2A, 0, 0, 0});
    EXPECT_EQ(read({"gw-a", 3, layout(), written}), FollowVerdict::apply);
    EXPECT_EQ(image(), written);
    rig_.persister().flush();
    EXPECT_EQ(rig_.store().load(make_plan()), written);
    EXPECT_EQ(images_.counters().followed, 1u);
    // The same image again (a reconnect's retained copy) changes nothing and counts nothing.
    EXPECT_EQ(read({"gw-a", 3, layout(), written}), FollowVerdict::apply);
    EXPECT_EQ(images_.counters().followed, 1u);
}

TEST_F(PairImagesTest, ALeaderKeepsItsOwnImage) {
    const auto before = image();
    EXPECT_EQ(read({"gw-a", 3, layout(), bytes({1, 2, 3, 4})}, true), FollowVerdict::leading);
    EXPECT_EQ(image(), before);
}

TEST_F(PairImagesTest, AnImageOfAnotherLayoutIsCountedAndLoggedOnce) {
    test::LogCapture log;
    const auto before = image();
    EXPECT_EQ(read({"gw-a", 3, layout() + 1, bytes({1, 2, 3, 4})}), FollowVerdict::other_layout);
    EXPECT_EQ(read({"gw-a", 3, layout() + 1, bytes({1, 2, 3, 5})}), FollowVerdict::other_layout);
    EXPECT_EQ(image(), before);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::other_layout), 2u);
    const auto lines = log.lines();
    EXPECT_EQ(std::count_if(lines.begin(), lines.end(),
                            [](const std::string& l) {
                                return l.find("another layout") != std::string::npos;
                            }),
              1)
        << ::testing::PrintToString(lines);
}

TEST_F(PairImagesTest, StaleUnknownAndMalformedImagesAreCountedAndLeftAlone) {
    const auto before = image();
    EXPECT_EQ(read({"gw-a", 2, layout(), bytes({1, 2, 3, 4})}), FollowVerdict::stale);
    EXPECT_EQ(
        images_.on_message(incoming({"gw-a", 3, layout(), bytes({1, 2, 3, 4})}, prefix + "/other"),
                           producers_, false, 3),
        FollowVerdict::unknown_exchange);
    EXPECT_FALSE(images_.on_message({topic, "not json"}, producers_, false, 3).has_value());
    // A topic cleared by hand is no image, and no fault either.
    EXPECT_FALSE(images_.on_message({topic, ""}, producers_, false, 3).has_value());
    EXPECT_EQ(image(), before);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::stale), 1u);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::unknown_exchange), 1u);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::not_an_image), 1u);
    EXPECT_EQ(images_.counters().followed, 0u);
}

// The leader answers a write `ok` only once the broker has the image carrying it.

TEST_F(PairImagesTest, AnAnswerWithNoImageOutstandingGoesAtOnce) {
    int answered = 0;
    images_.answer_after_image(producer(), [&] { ++answered; });
    EXPECT_EQ(answered, 1);
}

TEST_F(PairImagesTest, AnAnswerWaitsForTheImagePublishedBeforeItToBeAcknowledged) {
    images_.publish(producer(), 7);
    const auto token = publisher_.published.back().ack_token;
    ASSERT_NE(token, 0u);
    int answered = 0;
    images_.answer_after_image(producer(), [&] { ++answered; });
    EXPECT_EQ(answered, 0);
    // A lease's token (a time in nanoseconds) is not the images'.
    EXPECT_FALSE(images_.on_acknowledged(123456789, true));
    EXPECT_EQ(answered, 0);
    EXPECT_TRUE(images_.on_acknowledged(token, true));
    EXPECT_EQ(answered, 1);
    // Acknowledged: the next answer goes at once.
    images_.answer_after_image(producer(), [&] { ++answered; });
    EXPECT_EQ(answered, 2);
}

TEST_F(PairImagesTest, ANewerImageAcknowledgedStandsForTheOneItReplacedInTheQueue) {
    images_.publish(producer(), 7);
    int answered = 0;
    images_.answer_after_image(producer(), [&] { ++answered; });
    images_.publish(producer(), 7);
    images_.answer_after_image(producer(), [&] { ++answered; });
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, true));
    EXPECT_EQ(answered, 2);
    // The first one's acknowledgement, should it come after all, changes nothing.
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.front().ack_token, true));
    EXPECT_EQ(answered, 2);
}

TEST_F(PairImagesTest, AnswersOfAUnitThatNoLongerLeadsAreWithheld) {
    images_.publish(producer(), 7);
    int answered = 0;
    images_.answer_after_image(producer(), [&] { ++answered; });
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, false));
    images_.publish(producer(), 7);
    images_.answer_after_image(producer(), [&] { ++answered; });
    images_.withhold_answers();
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, true));
    EXPECT_EQ(answered, 0);
    EXPECT_EQ(images_.counters().answers_withheld, 2u);
}

}  // namespace
}  // namespace eip2mqtt::app::redundancy
