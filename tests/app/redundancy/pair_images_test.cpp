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
#include "eip2mqtt/core/redundancy/answer_key.hpp"
#include "tests/app/support/producer_rig.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/log_capture.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using core::redundancy::FollowVerdict;
using core::redundancy::ImageMessage;
using core::redundancy::ListedAnswer;
using core::redundancy::ListedResult;
using namespace std::chrono_literals;

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
    /// Write `id` of the producer, answered on `reply/{correlation}`.
    static WriteReply reply(const std::string& correlation) {
        return {"reply/" + correlation, correlation};
    }
    static std::uint64_t key(const std::string& correlation) {
        return core::redundancy::answer_key("reply/" + correlation, correlation);
    }
    /// `keys` as an older release's image lists them: not saying what each was answered.
    static std::vector<ListedAnswer> unknown(std::initializer_list<std::uint64_t> keys) {
        std::vector<ListedAnswer> listed;
        for (const auto k : keys) listed.push_back({k, ListedResult::unknown});
        return listed;
    }
    std::vector<std::uint64_t> listed_in(const adapters::mqtt::Message& message) {
        return decode_image_message(message.payload)->answers;
    }
    adapters::mqtt::Incoming incoming(const ImageMessage& image, const std::string& on = topic) {
        return {on, encode_image_message(image)};
    }
    std::optional<FollowVerdict> read(const ImageMessage& image, bool leading = false,
                                      std::uint64_t epoch = 3) {
        return images_.on_message(incoming(image), producers_, {leading, epoch, 0});
    }
    /// As leader under epoch 7, the unit owes write `a` its `ok` (counted in `answered`), its
    /// image published, and stands down before the broker had it.
    void owe_then_stand_down(int& answered) {
        images_.publish(producer(), 7);
        images_.answer_after_image(producer(), 1, reply("a"), t0_, [&answered] { ++answered; });
        images_.stood_down();
    }
    /// The broker sends this unit's newest image back (live, not retained) while this unit
    /// leads or not, having heard the other unit claim up to `others_epoch`.
    void hear_back(bool leading, std::uint64_t others_epoch) {
        const auto& sent = publisher_.published.back();
        images_.on_message({sent.topic, sent.payload}, producers_, {leading, 7, others_epoch});
    }

    core::MonoTime t0_{std::chrono::seconds(100)};
    test::ProducerRig rig_{"eip2mqtt_pair_images"};
    test::RecordingNorthbound northbound_;
    std::vector<std::unique_ptr<ExchangeProducer>> producers_;
    test::RecordingPublisher publisher_;
    PairImages images_{prefix, "gw-b", publisher_, 10s};
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
    EXPECT_EQ(decode_image_message(message.payload),
              (ImageMessage{"gw-b", 7, layout(), image(), {}, 1}));
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
                           producers_, {false, 3, 0}),
        FollowVerdict::unknown_exchange);
    EXPECT_FALSE(images_.on_message({topic, "not json"}, producers_, {false, 3, 0}).has_value());
    // A topic cleared by hand is no image, and no fault either.
    EXPECT_FALSE(images_.on_message({topic, ""}, producers_, {false, 3, 0}).has_value());
    EXPECT_EQ(image(), before);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::stale), 1u);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::unknown_exchange), 1u);
    EXPECT_EQ(images_.counters().ignored_for(ImageIgnored::not_an_image), 1u);
    EXPECT_EQ(images_.counters().followed, 0u);
}

// The leader answers a write `ok` only once the broker has an image listing it.

TEST_F(PairImagesTest, AWriteNoImageListedHasTheImagePublishedAgainListingIt) {
    int answered = 0;
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [&] { ++answered; });
    ASSERT_EQ(publisher_.published.size(), 1u);
    EXPECT_EQ(listed_in(publisher_.published.back()), std::vector<std::uint64_t>{key("a")});
    EXPECT_EQ(answered, 0);
    // A lease's token (a time in nanoseconds) is not the images'.
    EXPECT_FALSE(images_.on_acknowledged(123456789, true));
    EXPECT_EQ(answered, 0);
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, true));
    EXPECT_EQ(answered, 1);
    // Listed and acknowledged: the same write's answer (a save's) goes at once.
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [&] { ++answered; });
    EXPECT_EQ(answered, 2);
    EXPECT_EQ(publisher_.published.size(), 1u);
}

TEST_F(PairImagesTest, EachImageListsTheAnswersOfTheHorizonBeforeIt) {
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [] {});
    images_.answer_after_image(producer(), 2, reply("b"), t0_ + 1s, [] {});
    images_.publish(producer(), 7);
    EXPECT_EQ(listed_in(publisher_.published.back()),
              (std::vector<std::uint64_t>{key("a"), key("b")}));
    // Two writes sharing one key are listed twice: a standby drops as many.
    images_.answer_after_image(producer(), 3, reply("b"), t0_ + 10500ms, [] {});
    EXPECT_EQ(listed_in(publisher_.published.back()),
              (std::vector<std::uint64_t>{key("b"), key("b")}));
}

TEST_F(PairImagesTest, ANewerImageAcknowledgedStandsForTheOneItReplacedInTheQueue) {
    int answered = 0;
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [&] { ++answered; });
    images_.answer_after_image(producer(), 2, reply("b"), t0_, [&] { ++answered; });
    ASSERT_EQ(publisher_.published.size(), 2u);
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, true));
    EXPECT_EQ(answered, 2);
    // The first one's acknowledgement, should it come after all, changes nothing.
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.front().ack_token, true));
    EXPECT_EQ(answered, 2);
}

TEST_F(PairImagesTest, TheLeaderAnswersOnHearingItsImageBackAsWellAsOnItsAcknowledgement) {
    int answered = 0;
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [&] { ++answered; });
    hear_back(true, 0);
    EXPECT_EQ(answered, 1);
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, true));
    EXPECT_EQ(answered, 1);
    EXPECT_EQ(images_.counters().answers_late, 0u);
    // The image sent back retained (a resubscription's copy, perhaps from before a restart)
    // proves nothing about the order the broker took it in.
    images_.answer_after_image(producer(), 2, reply("b"), t0_, [&] { ++answered; });
    const auto& sent = publisher_.published.back();
    images_.on_message({sent.topic, sent.payload, true}, producers_, {true, 7, 0});
    EXPECT_EQ(answered, 1);
}

TEST_F(PairImagesTest, AUnitThatStoodDownAnswersWhenItHearsItsImageBeforeAnyOtherClaim) {
    int answered = 0;
    owe_then_stand_down(answered);
    // The acknowledgement alone decides nothing: claims the broker took before the image may
    // still be queued for this connection behind its window.
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, false));
    EXPECT_EQ(answered, 0);
    // The image comes back with no claim of the other unit before it (the broker was
    // stopped, say): whoever leads next reads it before its claim stands.
    hear_back(false, 6);
    EXPECT_EQ(answered, 1);
    EXPECT_EQ(images_.counters().answers_late, 1u);
}

TEST_F(PairImagesTest, AClaimHeardBeforeTheImageWithholdsTheAnswerWhateverTheAcknowledgementSaid) {
    int answered = 0;
    owe_then_stand_down(answered);
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, false));
    hear_back(false, 8);
    EXPECT_EQ(answered, 0);
    EXPECT_EQ(images_.counters().answers_withheld, 1u);
}

TEST_F(PairImagesTest, AClaimBeforeTheImageThatDidNotStandLetsTheAnswerGoWhenALaterOneLeads) {
    // The broker, stopped, takes on resuming the other unit's claim (epoch 8), the image, and
    // later the other unit's next claim (epoch 9), which stands: the other unit read the image
    // before it led, and leaves the write to this unit.
    int answered = 0;
    owe_then_stand_down(answered);
    hear_back(false, 8);
    images_.other_leads(7);  // a renewal from before this unit led: nothing known yet
    EXPECT_EQ(answered, 0);
    images_.other_leads(9);
    EXPECT_EQ(answered, 1);
    EXPECT_EQ(images_.counters().answers_late, 1u);
    images_.other_leads(10);
    images_.answer_withheld({}, t0_ + 1s, 10);
    EXPECT_EQ(answered, 1);
}

TEST_F(PairImagesTest, TheClaimThatCameBeforeTheImageStandingTheAnswerIsTheOtherUnits) {
    int answered = 0;
    owe_then_stand_down(answered);
    hear_back(false, 8);
    images_.other_leads(8);  // it led without having read the image: it settled the write
    images_.answer_withheld({}, t0_ + 1s, 8);
    EXPECT_EQ(answered, 0);
}

TEST_F(PairImagesTest, AnswersAreWithheldAfterAClaimOfTheOtherUnitOrAReconnect) {
    int answered = 0;
    owe_then_stand_down(answered);
    // The other unit's claim (epoch 8) came first: it may lead, and not have had the image.
    hear_back(false, 8);
    images_.publish(producer(), 9);
    images_.answer_after_image(producer(), 2, reply("b"), t0_, [&] { ++answered; });
    images_.reconnected();
    // Leading again, but not throughout: it stood down since the answer began waiting.
    images_.stood_down();
    EXPECT_TRUE(images_.on_acknowledged(publisher_.published.back().ack_token, true));
    EXPECT_EQ(answered, 0);
    EXPECT_EQ(images_.counters().answers_withheld, 2u);
}

TEST_F(PairImagesTest, LeadingAgainAnswersWhatItWithheldUnlessTheOtherUnitAnsweredIt) {
    std::vector<std::string> answered;
    images_.publish(producer(), 7);
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [&] { answered.push_back("a"); });
    images_.answer_after_image(producer(), 2, reply("b"), t0_, [&] { answered.push_back("b"); });
    images_.answer_after_image(producer(), 3, reply("c"), t0_, [&] { answered.push_back("c"); });
    images_.stood_down();
    hear_back(false, 8);
    EXPECT_TRUE(answered.empty());
    // The other unit led meanwhile and answered `b` (settled it by its image: it lists it).
    images_.answer_withheld(std::vector<ListedAnswer>{{key("b"), ListedResult::ok}}, t0_ + 5s, 0);
    EXPECT_EQ(answered, (std::vector<std::string>{"a", "c"}));
    EXPECT_EQ(images_.counters().answers_late, 2u);
    // Given once: leading again later answers nothing more.
    images_.answer_withheld({}, t0_ + 6s, 0);
    EXPECT_EQ(answered.size(), 2u);
}

TEST_F(PairImagesTest, AnAnswerWithheldBeyondTheHorizonIsNotGivenLateOnceTheOtherUnitLed) {
    int answered = 0;
    owe_then_stand_down(answered);
    hear_back(false, 8);
    images_.other_leads(8);
    images_.answer_withheld({}, t0_ + 11s, 8);
    EXPECT_EQ(answered, 0);
}

TEST_F(PairImagesTest, AnAnswerWithheldBeyondTheHorizonIsGivenWhenNobodyElseLedSince) {
    // The broker stopped for longer than the horizon: the other unit's claim came first, but
    // never stood, and this unit leads again.
    int answered = 0;
    owe_then_stand_down(answered);
    hear_back(false, 8);
    images_.other_leads(6);  // an old renewal, from before this unit led
    images_.answer_withheld({}, t0_ + 11s, 6);
    EXPECT_EQ(answered, 1);
}

TEST_F(PairImagesTest, ARefusalSettledByANewLeaderIsListedInItsNextImage) {
    images_.list_refusal(producer().plan(), key("r"), t0_);
    images_.publish(producer(), 9);
    EXPECT_EQ(listed_in(publisher_.published.back()), std::vector<std::uint64_t>{key("r")});
    // Said a refusal, where the writes it answered `ok` are not.
    images_.answer_after_image(producer(), 1, reply("a"), t0_, [] {});
    const auto image = decode_image_message(publisher_.published.back().payload);
    EXPECT_EQ(image->answers, (std::vector<std::uint64_t>{key("r"), key("a")}));
    EXPECT_EQ(image->refused, std::vector<std::uint64_t>{key("r")});
}

TEST_F(PairImagesTest, ATakeoverTakesTheAnswersTheOtherUnitsNewestImagesList) {
    ImageMessage leader{"gw-a", 3, layout(), image(), {key("a")}};
    read(leader);
    leader.answers = {key("a"), key("b")};
    read(leader);
    // This unit's own image is not heard, nor one read as leader.
    read({"gw-b", 3, layout(), image(), {key("d")}});
    read({"gw-a", 3, layout(), image(), {key("e")}}, true);
    EXPECT_EQ(images_.take_leader_answers(), unknown({key("a"), key("b")}));
    // A deposed leader's, read late, is: it answers those late if its image came before the
    // claim that stood, which is this unit's, taking them now.
    read({"gw-a", 2, layout(), image(), {key("c")}});
    // One read after this unit's claim came back came after the claim: its publisher withholds
    // what it lists, and leaves it to this unit.
    images_.on_message(incoming({"gw-a", 2, layout(), image(), {key("f")}}), producers_,
                       {false, 3, 0, true});
    EXPECT_EQ(images_.take_leader_answers(), unknown({key("c")}));
    EXPECT_TRUE(images_.take_leader_answers().empty());
}

TEST_F(PairImagesTest, ATakeoverTakesWhatTheImagesSayEachWriteWasAnswered) {
    ImageMessage leader{"gw-a", 3, layout(), image(), {key("a"), key("r")}};
    leader.refused = std::vector<std::uint64_t>{key("r")};
    read(leader);
    EXPECT_EQ(images_.take_leader_answers(),
              (std::vector<ListedAnswer>{{key("a"), ListedResult::ok},
                                         {key("r"), ListedResult::refused}}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
