// Writes in a payload profile's own shapes (docs/mqtt-api.md, "Payload profiles"), beside the
// json forms every profile takes, and what each profile still refuses.

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "eip2mqtt/app/northbound/json_tree/write_payload.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::config::PayloadFormat;
using core::write::WriteError;
using core::write::WriteInput;

WriteInput tag_input(std::string_view payload, PayloadFormat profile) {
    const auto result = parse_tag_write(payload, profile);
    EXPECT_TRUE(result.ok()) << payload << ": " << (result.ok() ? "" : result.error().message);
    return result.ok() ? result.value() : WriteInput{false};
}

WriteError tag_refused(std::string_view payload, PayloadFormat profile) {
    const auto result = parse_tag_write(payload, profile);
    EXPECT_FALSE(result.ok()) << payload;
    return result.ok() ? WriteError::empty : result.error().error;
}

TEST(ProfileWrites, UmhTakesItsTimestampAndLeavesItToTheGateway) {
    EXPECT_EQ(tag_input(R"({"value": 42, "timestamp_ms": 1700000000000})", PayloadFormat::umh),
              WriteInput{std::uint64_t{42}});
    EXPECT_EQ(tag_input(R"({"value": 1.5})", PayloadFormat::umh), WriteInput{1.5});
    // Not a time: still malformed, and other profiles know no timestamp_ms.
    EXPECT_EQ(tag_refused(R"({"value": 42, "timestamp_ms": "now"})", PayloadFormat::umh),
              WriteError::malformed);
    EXPECT_EQ(tag_refused(R"({"value": 42, "timestamp_ms": 1})", PayloadFormat::json),
              WriteError::malformed);
}

TEST(ProfileWrites, KepwareTakesVOnATagAndRecordsOnAnExchange) {
    EXPECT_EQ(tag_input(R"({"v": 3100})", PayloadFormat::kepware), WriteInput{std::uint64_t{3100}});
    EXPECT_EQ(tag_refused(R"({"v": 3100})", PayloadFormat::json), WriteError::malformed);
    const auto records =
        parse_exchange_write(R"([{"id": "sp.SPEED_SP", "v": 3100}, {"id": "START", "v": true}])",
                             PayloadFormat::kepware);
    ASSERT_TRUE(records.ok()) << records.error().message;
    ASSERT_EQ(records.value().size(), 2u);
    EXPECT_EQ(records.value()[0].first, "sp.SPEED_SP");
    EXPECT_EQ(records.value()[0].second, WriteInput{std::uint64_t{3100}});
    EXPECT_EQ(records.value()[1].second, WriteInput{true});
    // The json object form still works under kepware.
    EXPECT_TRUE(parse_exchange_write(R"({"START": false})", PayloadFormat::kepware).ok());
}

TEST(ProfileWrites, KepwareRecordsAreFlatAndWhole) {
    for (const auto* payload :
         {R"([])", R"([{"id": "A"}])", R"([{"id": "A", "v": 1, "q": true}])",
          R"([{"id": 5, "v": 1}])", R"([{"id": "A", "v": {"x": 1}}])",
          R"([{"id": "A", "v": [[1]]}])", R"([[{"id": "A", "v": 1}]])",
          R"([{"id": "A", "v": 1}, 2])", R"([{"id": "A", "id": "B", "v": 1}])"}) {
        const auto result = parse_exchange_write(payload, PayloadFormat::kepware);
        EXPECT_FALSE(result.ok()) << payload;
    }
    // Records are Kepware's alone: json refuses an array of them.
    EXPECT_FALSE(parse_exchange_write(R"([{"id": "A", "v": 1}])", PayloadFormat::json).ok());
}

TEST(ProfileWrites, ValueTakesTextThatIsNotJsonAsAStringsText) {
    EXPECT_EQ(tag_input("B-18", PayloadFormat::value), WriteInput{std::string("B-18")});
    EXPECT_EQ(tag_input("\"quoted\"", PayloadFormat::value), WriteInput{std::string("quoted")});
    EXPECT_EQ(tag_input("42", PayloadFormat::value), WriteInput{std::uint64_t{42}});
    EXPECT_EQ(tag_refused("B-18", PayloadFormat::json), WriteError::malformed);
    EXPECT_EQ(tag_refused("", PayloadFormat::value), WriteError::malformed);
    EXPECT_EQ(tag_refused(std::string_view("a\0b", 3), PayloadFormat::value),
              WriteError::malformed);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
