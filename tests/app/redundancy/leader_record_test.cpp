// The leader record's JSON (docs/schema/leader.json): what a unit writes, what it reads back,
// and what it does not read as a record.

#include "eip2mqtt/app/redundancy/leader_record.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::redundancy::LeaderRecord;

TEST(LeaderRecordTest, EveryRecordCarriesItsBeatAndAClaimWhatItHeard) {
    LeaderRecord claim{"gw-b", 3, 0, true};
    claim.beat = 5000;
    claim.heard = core::redundancy::LeaderMark{"gw-a", 2, 4000};
    const auto payload = encode_leader_record(claim, 2000ms);
    EXPECT_EQ(payload, R"({"beat":5000,"claim":true,"epoch":3,"heard":{"beat":4000,"epoch":2,)"
                       R"("id":"gw-a"},"id":"gw-b","priority":0,"takeover_ms":2000})");
    const auto read = decode_leader_record(payload);
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->beat, 5000u);
    EXPECT_EQ(read->heard, claim.heard);
    // Of an earlier version: beat 0, a claim that heard nothing; a renewal hears nothing.
    const auto old = decode_leader_record(R"({"id":"a","epoch":1,"claim":true})");
    EXPECT_EQ(old->beat, 0u);
    EXPECT_FALSE(old->heard.has_value());
    const auto renewal = decode_leader_record(
        R"({"id":"a","epoch":1,"beat":7,"heard":{"id":"b","epoch":1,"beat":1}})");
    EXPECT_EQ(renewal->beat, 7u);
    EXPECT_FALSE(renewal->heard.has_value());
    EXPECT_FALSE(decode_leader_record(R"({"id":"a","epoch":1,"claim":true,"heard":{"id":"b"}})")
                     ->heard.has_value());
}

TEST(LeaderRecordTest, EncodedAndDecoded) {
    const auto payload = encode_leader_record({"gw-a", 7, 100}, 2000ms);
    EXPECT_EQ(payload, R"({"epoch":7,"id":"gw-a","priority":100,"takeover_ms":2000})");
    EXPECT_EQ(decode_leader_record(payload), (LeaderRecord{"gw-a", 7, 100}));
}

TEST(LeaderRecordTest, ARenewalCarriesTheBdSeqOfTheSparkplugSession) {
    LeaderRecord record{"gw-a", 7, 100};
    record.bd_seq = 255;
    const auto payload = encode_leader_record(record, 2000ms);
    EXPECT_EQ(payload, R"({"bd_seq":255,"epoch":7,"id":"gw-a","priority":100,"takeover_ms":2000})");
    EXPECT_EQ(decode_leader_record(payload), record);
    for (const char* other :
         {R"({"id":"a","epoch":1,"bd_seq":256})", R"({"id":"a","epoch":1,"bd_seq":-1})",
          R"({"id":"a","epoch":1,"bd_seq":"3"})"}) {
        const auto read = decode_leader_record(other);
        ASSERT_TRUE(read.has_value()) << other;
        EXPECT_FALSE(read->bd_seq.has_value()) << other;
    }
}

TEST(LeaderRecordTest, WatermarksEncodedAndDecoded) {
    const Watermarks watermarks{{"line/1", {4711, 1695231678, 123456789}},
                                {"line/2", {65535, 0, 0, 2}}};
    const auto payload = encode_leader_record({"gw-a", 7, 100}, 2000ms, watermarks);
    EXPECT_EQ(payload, R"({"epoch":7,"id":"gw-a","priority":100,"takeover_ms":2000,"watermarks":)"
                       R"({"line/1":[4711,1695231678,123456789],"line/2":[65535,0,0,2]}})");
    Watermarks read{{"stale", {}}};
    EXPECT_EQ(decode_leader_record(payload, &read), (LeaderRecord{"gw-a", 7, 100}));
    EXPECT_EQ(read, watermarks);
    // None without: what was there before goes.
    decode_leader_record(encode_leader_record({"gw-a", 7, 100}, 2000ms), &read);
    EXPECT_TRUE(read.empty());
}

TEST(LeaderRecordTest, AWatermarkThatIsNoSampleIsLeftOut) {
    Watermarks read;
    const auto record = decode_leader_record(
        R"({"id":"a","epoch":1,"watermarks":{"ok":[1,2,3],"short":[1,2],"long":[1,2,3,4,5],)"
        R"("rid":[65536,0,0],"ns":[1,0,1000000000],"change":[1,0,0,256],"neg":[-1,0,0],)"
        R"("text":"1,2,3"}})",
        &read);
    ASSERT_TRUE(record.has_value());
    EXPECT_EQ(read, (Watermarks{{"ok", {1, 2, 3}}}));
    decode_leader_record(R"({"id":"a","epoch":1,"watermarks":[1]})", &read);
    EXPECT_TRUE(read.empty());
}

TEST(LeaderRecordTest, WhatIsNoRecordReadsAsNone) {
    for (const char* payload :
         {"", "null", "[]", R"({"id":"a"})", R"({"epoch":1})", R"({"id":"","epoch":1})",
          R"({"id":"a","epoch":-1})", R"({"id":3,"epoch":1})", "{"}) {
        EXPECT_FALSE(decode_leader_record(payload).has_value()) << payload;
    }
    EXPECT_EQ(decode_leader_record(R"({"id":"a","epoch":1,"priority":70000})")->priority, 0);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
