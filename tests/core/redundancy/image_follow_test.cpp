#include "eip2mqtt/core/redundancy/image_follow.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

constexpr std::uint64_t layout = 0x1234'5678'9abc'def0ULL;

ImageMessage image(std::uint64_t epoch, std::size_t length = 4,
                   std::uint64_t fingerprint = layout) {
    return {"gw-a", epoch, fingerprint, std::vector<std::byte>(length, std::byte{0x45})};
}

FollowContext standby(std::uint64_t epoch) { return {false, epoch, ImageLayout{layout, 4}}; }

TEST(ImageFollow, AStandbyTakesAnImageOfItsLayoutFromTheLeaderItFollows) {
    EXPECT_EQ(judge_image(image(3), standby(3)), FollowVerdict::apply);
}

TEST(ImageFollow, ALeaderNeverTakesAnImage) {
    auto context = standby(3);
    context.leading = true;
    EXPECT_EQ(judge_image(image(3), context), FollowVerdict::leading);
    EXPECT_EQ(judge_image(image(4), context), FollowVerdict::leading);
}

TEST(ImageFollow, AnExchangeTheUnitDoesNotProduceIsUnknown) {
    auto context = standby(3);
    context.producer.reset();
    EXPECT_EQ(judge_image(image(3), context), FollowVerdict::unknown_exchange);
}

TEST(ImageFollow, AnImageOfAnotherLayoutIsIgnored) {
    EXPECT_EQ(judge_image(image(3, 4, layout + 1), standby(3)), FollowVerdict::other_layout);
    // The same fingerprint with another number of bytes is no image of this exchange either.
    EXPECT_EQ(judge_image(image(3, 5), standby(3)), FollowVerdict::other_layout);
    EXPECT_EQ(judge_image(image(3, 0), standby(3)), FollowVerdict::other_layout);
}

TEST(ImageFollow, ADeposedLeadersImageThatComesLateIsStale) {
    EXPECT_EQ(judge_image(image(2), standby(3)), FollowVerdict::stale);
}

TEST(ImageFollow, AnImageOfANewerEpochOrReadBeforeAnyLeaderIsTaken) {
    // A retained image read at start-up, before the leader's record, or of a pair whose epochs
    // began again after both units restarted.
    EXPECT_EQ(judge_image(image(5), standby(0)), FollowVerdict::apply);
    EXPECT_EQ(judge_image(image(4), standby(3)), FollowVerdict::apply);
}

TEST(ImageFollow, EachListedAnswerSaysItsResultWhereTheImageSaysThem) {
    auto listing = image(3);
    listing.answers = {7, 8, 7, 9};
    EXPECT_EQ(listed_answers(listing), (std::vector<ListedAnswer>{{7, ListedResult::unknown},
                                                                  {8, ListedResult::unknown},
                                                                  {7, ListedResult::unknown},
                                                                  {9, ListedResult::unknown}}))
        << "an older release's image does not say";
    // A key shared by two writes (no correlation data) and refused once: its first listing.
    listing.refused = std::vector<std::uint64_t>{7};
    EXPECT_EQ(listed_answers(listing), (std::vector<ListedAnswer>{{7, ListedResult::refused},
                                                                  {8, ListedResult::ok},
                                                                  {7, ListedResult::ok},
                                                                  {9, ListedResult::ok}}));
    listing.refused->push_back(5);  // a refusal not among the answers lists nothing
    EXPECT_EQ(listed_answers(listing).size(), 4u);
}

TEST(ImageFollow, RequestIdsContinueAfterTheLastHeardAndWrap) {
    EXPECT_EQ(request_id_after(41), 42);
    EXPECT_EQ(request_id_after(65535), 0);
    EXPECT_EQ(request_id_after(0), 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
