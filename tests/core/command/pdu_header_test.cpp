#include "eip2mqtt/core/command/pdu_header.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "eip2mqtt/core/command/command_status.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

TEST(PduTypes, EachRequestIsAnsweredByTheNextType) {
    int requests = 0;
    for (int byte = 0; byte < 256; ++byte) {
        const auto type = pdu_type_of(static_cast<std::uint8_t>(byte));
        if (!type || !is_request(*type)) continue;
        ++requests;
        const auto response = response_type_of(*type);
        ASSERT_TRUE(response.has_value());
        EXPECT_EQ(static_cast<int>(*response), byte + 1);
        EXPECT_FALSE(is_request(*response));
    }
    EXPECT_EQ(requests, 7);
    EXPECT_FALSE(response_type_of(PduType::nak).has_value());
}

TEST(PduTypes, FifteenTypesWithDistinctNames) {
    std::set<std::string> names;
    for (int byte = 0; byte < 256; ++byte) {
        if (const auto type = pdu_type_of(static_cast<std::uint8_t>(byte))) {
            names.emplace(to_string(*type));
        }
    }
    EXPECT_EQ(names.size(), 15u);
    EXPECT_FALSE(pdu_type_of(0x0D).has_value());
}

TEST(PduHeader, ReplyEchoesFlagAndRequestId) {
    PduHeader request;
    request.type = PduType::summary_request;
    request.flag = 7;
    request.request_id = 0xBEEF;
    const auto reply = reply_header(request, PduType::summary_response, 3);
    EXPECT_EQ(reply.type, PduType::summary_response);
    EXPECT_EQ(reply.flag, 7);
    EXPECT_EQ(reply.request_id, 0xBEEF);
    EXPECT_EQ(reply.status, 3);
    EXPECT_EQ(reply.version, 1);
}

TEST(CommandStatus, EveryStatusHasANameAndRoundTrips) {
    for (int byte = 0; byte < 256; ++byte) {
        const auto status = command_status_of(static_cast<std::uint8_t>(byte));
        if (byte <= 9) {
            ASSERT_TRUE(status.has_value()) << byte;
            EXPECT_NE(to_string(*status), "unknown");
        } else {
            EXPECT_FALSE(status.has_value()) << byte;
        }
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
