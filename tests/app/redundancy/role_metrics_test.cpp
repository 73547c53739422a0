// The role's counters in the metrics topic: a pair's `pair` object, none for a single unit.

#include "eip2mqtt/app/redundancy/role_metrics.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/app/health/metrics.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

struct RoleMetricsTest : ::testing::Test {
    DatagramCounters datagrams;
    WriteCounters writes;
    MetricsSources sources{datagrams, writes};  // the main connection's stats: sources.mqtt
};

TEST_F(RoleMetricsTest, ASingleUnitAddsNothing) {
    nlohmann::json metrics = nlohmann::json::object();
    add_role_metrics(metrics, sources);
    EXPECT_TRUE(metrics.empty());
}

TEST_F(RoleMetricsTest, APairAddsItsObjectWithTheHeardDatagramsAndTheFencedPublications) {
    PairImageCounters images;
    images.published = 3;
    images.ignored[1] = 2;
    datagrams.produced_heard = 5;
    sources.mqtt.discarded = 7;
    sources.pair_images = &images;
    nlohmann::json metrics = nlohmann::json::object();
    add_role_metrics(metrics, sources);
    const auto& pair = metrics.at("pair");
    EXPECT_EQ(pair.at("images_published"), 3);
    EXPECT_EQ(pair.at("images_ignored").at("stale"), 2);
    EXPECT_EQ(pair.at("produced_heard"), 5);
    EXPECT_EQ(pair.at("publications_fenced"), 7);
    EXPECT_EQ(pair.at("samples_replayed"), 0);  // no history: its counters read zero
    EXPECT_EQ(pair.at("answers_heard"), 0);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
