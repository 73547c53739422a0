#include "eip2mqtt/core/redundancy/sample_key.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

constexpr SampleKey untimed(std::uint16_t request_id, std::uint8_t change = 0) {
    return {request_id, 0, 0, change};
}

TEST(SampleKey, ARequestIdAheadIsNewerAcrossTheWrap) {
    EXPECT_TRUE(comes_after(untimed(11), untimed(10)));
    EXPECT_FALSE(comes_after(untimed(10), untimed(11)));
    EXPECT_TRUE(comes_after(untimed(2), untimed(65534)));
    EXPECT_FALSE(comes_after(untimed(65534), untimed(2)));
    EXPECT_TRUE(comes_after(untimed(10 + 32767), untimed(10)));
    EXPECT_FALSE(comes_after(untimed(10 + 32768), untimed(10)));
}

TEST(SampleKey, ASampleIsNotNewerThanItself) {
    EXPECT_FALSE(comes_after(untimed(10), untimed(10)));
    const SampleKey timed{10, 1700000000, 5};
    EXPECT_FALSE(comes_after(timed, timed));
}

TEST(SampleKey, AChangeOfQualityComesAfterItsDatagram) {
    EXPECT_TRUE(comes_after(untimed(10, 1), untimed(10)));
    EXPECT_TRUE(comes_after(untimed(10, 2), untimed(10, 1)));
    EXPECT_FALSE(comes_after(untimed(10, 1), untimed(10, 2)));
    EXPECT_TRUE(comes_after(untimed(11), untimed(10, 3)));
}

TEST(SampleKey, AProducerThatRestartedIsNewerByItsTimestamp) {
    // Rule 6: request ids behind, the producer's time ahead (both non-zero): a restart.
    const SampleKey before{1000, 1700000000, 0};
    const SampleKey restarted{1, 1700000005, 0};
    EXPECT_TRUE(comes_after(restarted, before));
    // A request id behind whose time went back too is older.
    EXPECT_FALSE(comes_after(SampleKey{1, 1699999995, 0}, before));
    // Without timestamps a request id behind is only older.
    EXPECT_FALSE(comes_after(untimed(1), untimed(1000)));
    EXPECT_FALSE(comes_after(SampleKey{1, 1700000005, 0}, untimed(1000)));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
