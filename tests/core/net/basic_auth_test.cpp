// HTTP basic authentication's header value (RFC 7617's own example) and its comparison.

#include "eip2mqtt/core/net/basic_auth.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::net {
namespace EIP2MQTT_THIS_FILE {

TEST(BasicAuth, TheHeaderValueOfRfc7617sExample) {
    EXPECT_EQ(basic_authorization("Aladdin", "open sesame"), "Basic QWxhZGRpbjpvcGVuIHNlc2FtZQ==");
}

TEST(BasicAuth, EachPaddingLengthAndBytesAboveAscii) {
    EXPECT_EQ(basic_authorization("", ""), "Basic Og==");                             // ":"
    EXPECT_EQ(basic_authorization("a", ""), "Basic YTo=");                            // "a:"
    EXPECT_EQ(basic_authorization("ab", ""), "Basic YWI6");                           // "ab:"
    EXPECT_EQ(basic_authorization("test", "123\xc2\xa3"), "Basic dGVzdDoxMjPCow==");  // RFC 7617
}

TEST(BasicAuth, TheSameSecretOnlyWhenEveryByteIs) {
    EXPECT_TRUE(same_secret("Basic YTo=", "Basic YTo="));
    EXPECT_FALSE(same_secret("Basic YTo=", "Basic YTp="));
    EXPECT_FALSE(same_secret("Basic YTo", "Basic YTo="));
    EXPECT_FALSE(same_secret("", "Basic YTo="));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::net
