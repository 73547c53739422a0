// The pair's own connection: its options (pair_client_options) and the real connector, which
// makes an MQTT client that does not connect before start(). Its use by the Pair is tested in
// pair_role_test.cpp, against a fake broker.

#include "eip2mqtt/app/redundancy/pair_connection.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

#include "eip2mqtt/app/redundancy/pair_lease.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

core::config::Config config() {
    core::config::Config c;
    c.gateway.id = "gw-a";
    c.mqtt.base_topic = "acme";
    c.mqtt.session_expiry = 3600s;  // the tag tree's session is kept; the pair's never is
    c.redundancy.pair = "turbine";
    return c;
}

TEST(PairConnectionTest, ItsOwnCleanSessionBoundConnectionThatHearsItself) {
    const auto will = pair_will(pair_topics("acme", "turbine", "gw-a"));
    const auto options = pair_client_options(config(), will);
    EXPECT_EQ(options.client_id, "eip2mqtt-gw-a-pair");
    EXPECT_EQ(options.log_name, "MQTT (pair)");
    EXPECT_EQ(options.session_expiry, 0s);
    EXPECT_TRUE(options.clean_start);
    EXPECT_TRUE(options.session_bound);
    EXPECT_TRUE(options.hear_own);
    EXPECT_FALSE(options.retain_as_published);
    EXPECT_TRUE(options.availability_topic.empty());
    EXPECT_EQ(options.subscription_qos, 1);
    auto over_311 = config();
    over_311.mqtt.version = 3;
    over_311.mqtt.session_expiry = 3600s;  // the user's session; the pair's is always clean
    EXPECT_EQ(pair_client_options(over_311, will).subscription_qos, 0);
    ASSERT_TRUE(options.will);
    const auto made = options.will();
    EXPECT_EQ(made.topic, will.topic);
    EXPECT_TRUE(made.payload.empty());
    EXPECT_TRUE(made.retain);
}

TEST(PairConnectionTest, TheRealConnectorMakesAClientNotConnectedBeforeStart) {
    boost::asio::io_context loop;
    auto connection = mqtt_pair_connector(loop.get_executor())(
        config(), pair_will(pair_topics("acme", "turbine", "gw-a")));
    ASSERT_NE(connection, nullptr);
    EXPECT_FALSE(connection->connected());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
