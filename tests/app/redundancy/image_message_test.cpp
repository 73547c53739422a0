#include "eip2mqtt/app/redundancy/image_message.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/schema_check.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using core::redundancy::ImageMessage;

ImageMessage sample() {
    return {"gw-a",
            3,
            0x8c1f'0e5a'2b3d'4c6eULL,
            {std::byte{0x00}, std::byte{0x80}, std::byte{0x3b}, std::byte{0x45}},
            {}};
}

TEST(ImageMessage, EncodesTheLayoutAndDataInHex) {
    const auto payload = encode_image_message(sample());
    EXPECT_EQ(
        nlohmann::json::parse(payload),
        nlohmann::json(
            {{"id", "gw-a"}, {"epoch", 3}, {"layout", "8c1f0e5a2b3d4c6e"}, {"data", "00803b45"}}));
    EXPECT_EQ(test::schema_problem(test::schema_file("pair-image.json"), payload), "");
}

TEST(ImageMessage, DecodesWhatItEncodes) {
    EXPECT_EQ(decode_image_message(encode_image_message(sample())), sample());
    auto large = sample();
    large.layout = ~std::uint64_t{0};
    large.data.assign(1400, std::byte{0xA5});
    EXPECT_EQ(decode_image_message(encode_image_message(large)), large);
    EXPECT_EQ(
        decode_image_message(R"({"id":"b","epoch":0,"layout":"0000000000000001","data":"FFfe"})"),
        (ImageMessage{"b", 0, 1, {std::byte{0xFF}, std::byte{0xFE}}, {}}));
}

TEST(ImageMessage, ListsTheAnswersOfItsWritesAsSixteenHexDigitsEach) {
    auto image = sample();
    image.answers = {0x5d2a'0000'0000'0001ULL, ~std::uint64_t{0}, 0};
    const auto payload = encode_image_message(image);
    EXPECT_EQ(nlohmann::json::parse(payload)["answers"],
              nlohmann::json({"5d2a000000000001", "ffffffffffffffff", "0000000000000000"}));
    EXPECT_EQ(test::schema_problem(test::schema_file("pair-image.json"), payload), "");
    EXPECT_EQ(decode_image_message(payload), image);
    // Absent, the list is empty: an image of a unit that answered nothing, or of an older
    // release, reads as before.
    EXPECT_EQ(decode_image_message(encode_image_message(sample()))->answers.size(), 0u);
}

TEST(ImageMessage, SaysWhichOfItsAnswersWereRefusals) {
    auto image = sample();
    image.answers = {1, 2};
    image.refused = std::vector<std::uint64_t>{2};
    const auto payload = encode_image_message(image);
    EXPECT_EQ(nlohmann::json::parse(payload)["refused"], nlohmann::json({"0000000000000002"}));
    EXPECT_EQ(test::schema_problem(test::schema_file("pair-image.json"), payload), "");
    EXPECT_EQ(decode_image_message(payload), image);
    // None refused is said too: what tells an image that says from an older release's.
    image.refused->clear();
    EXPECT_EQ(nlohmann::json::parse(encode_image_message(image))["refused"],
              nlohmann::json::array());
    EXPECT_EQ(decode_image_message(encode_image_message(image)), image);
    image.refused.reset();
    EXPECT_FALSE(nlohmann::json::parse(encode_image_message(image)).contains("refused"));
    EXPECT_EQ(decode_image_message(encode_image_message(image)), image);
}

TEST(ImageMessage, CarriesItsNumberWhenItHasOne) {
    auto image = sample();
    image.seq = 42;
    const auto payload = encode_image_message(image);
    EXPECT_EQ(nlohmann::json::parse(payload)["seq"], 42);
    EXPECT_EQ(test::schema_problem(test::schema_file("pair-image.json"), payload), "");
    EXPECT_EQ(decode_image_message(payload), image);
    EXPECT_FALSE(decode_image_message(
        R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"00","seq":"1"})"));
}

TEST(ImageMessage, WhatIsNoImageDecodesToNothing) {
    for (const char* payload :
         {"", "null", "[]", "{", R"({"epoch":1,"layout":"0000000000000001","data":"00"})",
          R"({"id":"a","layout":"0000000000000001","data":"00"})",
          R"({"id":"a","epoch":-1,"layout":"0000000000000001","data":"00"})",
          R"({"id":"a","epoch":1,"layout":"01","data":"00"})",
          R"({"id":"a","epoch":1,"layout":"000000000000000g","data":"00"})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"0"})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"zz"})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001"})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"00","answers":"01"})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"00","answers":[1]})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"00","answers":["01"]})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"00","refused":{}})",
          R"({"id":"a","epoch":1,"layout":"0000000000000001","data":"00","refused":[2]})"}) {
        EXPECT_FALSE(decode_image_message(payload).has_value()) << payload;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
