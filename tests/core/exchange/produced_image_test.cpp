#include "eip2mqtt/core/exchange/produced_image.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using plan::TagType;
using plan::Value;
using test::from_hex;
using test::to_hex;

plan::TagPlan tag(std::string name, std::string_view address, TagType type,
                  std::optional<Value> initial = std::nullopt) {
    plan::TagPlan tag;
    tag.spec.name = std::move(name);
    tag.spec.address = *plan::parse_address(address);
    tag.spec.type = type;
    tag.spec.writable = true;
    tag.spec.mutable_extras().initial = initial;
    return tag;
}

/// 8 data bytes: SPEED_SP real at 0, START bit 4.0, MODE bit 4.1, OFFSET int at 5, byte 7 free.
plan::ExchangePlan make_plan() {
    plan::ExchangePlan plan;
    plan.spec.name = "setpoints";
    plan.spec.direction = plan::Direction::produce;
    plan.spec.producer_id = *wire::parse_producer_id("10.0.0.5");
    plan.spec.exchange_id = 7;
    plan.spec.signature = wire::Signature{2, 5};
    plan.length = 8;
    plan.tags = {
        tag("SPEED_SP", "0", TagType::real, Value{std::int64_t{3000}}),
        tag("START", "4.0", TagType::bit, Value{true}),
        tag("MODE", "4.1", TagType::bit),
        tag("OFFSET", "5", TagType::int_, Value{std::int64_t{-2}}),
    };
    return plan;
}

constexpr std::size_t speed_sp = 0;
constexpr std::size_t start = 1;
constexpr std::size_t mode = 2;
constexpr std::size_t offset = 3;

/// 2023-11-14 22:13:20.123456789 UTC: 1700000000 s (0x6553F100), 123456789 ns (0x075BCD15).
const WallTime wall = WallTime{} + std::chrono::seconds{1700000000} + 123456789ns;

struct Produced {
    std::string hex;
    std::vector<std::uint64_t> carried;
};

Produced produce(ProducedImage& image, WallTime when = wall) {
    std::vector<std::byte> out(wire::max_datagram_size, std::byte{0xEE});
    Produced produced;
    const std::size_t size = image.produce(when, out, produced.carried);
    out.resize(size);
    produced.hex = to_hex(out);
    return produced;
}

std::string data_hex(const ProducedImage& image) { return to_hex(image.data()); }

write::WriteBatch batch(std::uint64_t id, std::vector<write::TagWrite> writes) {
    return {id, std::move(writes)};
}

TEST(ProducedImage, StartsFromZerosAndInitialValuesWithoutARestoredImage) {
    const auto plan = make_plan();
    const ProducedImage image(plan, {});
    EXPECT_FALSE(image.restored());
    // 3000.0f = 0x453B8000; START set, MODE clear; -2 as i16 = 0xFFFE.
    EXPECT_EQ(data_hex(image), "00803b4501feff00");
}

TEST(ProducedImage, InitialValuesApplyWhenTheRestoredImageHasAnotherLength) {
    const auto plan = make_plan();
    const auto restored = from_hex("1122334455");
    const ProducedImage image(plan, restored);
    EXPECT_FALSE(image.restored());
    EXPECT_EQ(data_hex(image), "00803b4501feff00");
}

TEST(ProducedImage, RestoredImageOfTheRightLengthWins) {
    const auto plan = make_plan();
    const auto restored = from_hex("1122334455667788");
    const ProducedImage image(plan, restored);
    EXPECT_TRUE(image.restored());
    EXPECT_EQ(data_hex(image), "1122334455667788");
    EXPECT_FALSE(image.dirty());
}

TEST(ProducerRules, HeaderBytesAreExact) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    const auto produced = produce(image);
    EXPECT_EQ(produced.hex,
              "0d01"      // PDU type, version
              "0100"      // request id 1
              "0a000005"  // producer id in dotted order
              "07000000"  // exchange id
              "00f15365"  // seconds
              "15cd5b07"  // nanoseconds
              "00000000"  // status
              "05020000"  // signature: minor = byte 24, major = byte 25 (as V5)
              "00000000"  // reserved
              "00803b4501feff00");
    EXPECT_TRUE(produced.carried.empty());
}

TEST(ProducerRules, SignatureZeroWhenNotConfigured) {
    auto plan = make_plan();
    plan.spec.signature = {};
    ProducedImage image(plan, {});
    EXPECT_EQ(produce(image).hex.substr(48, 16), "0000000000000000");
}

TEST(ProducerRules, DatagramDecodesAsItsOwnExchange) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    const auto bytes = from_hex(produce(image).hex);
    const auto datagram = wire::decode_datagram(bytes);
    ASSERT_TRUE(datagram.ok());
    EXPECT_EQ(datagram->header.key(), plan.key());
    EXPECT_EQ(wire::Signature::from_wire(datagram->header.signature), plan.spec.signature);
    EXPECT_EQ(datagram->data.size(), plan.length);
}

TEST(ProducerRules, RequestIdStartsAtOneIncrementsAndWraps) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    EXPECT_EQ(image.next_request_id(), ProducedImage::first_request_id);
    EXPECT_EQ(produce(image).hex.substr(4, 4), "0100");
    EXPECT_EQ(produce(image).hex.substr(4, 4), "0200");
    std::vector<std::byte> out(wire::max_datagram_size);
    std::vector<std::uint64_t> carried;
    while (image.next_request_id() != 65535) image.produce(wall, out, carried);
    EXPECT_EQ(produce(image).hex.substr(4, 4), "ffff");
    EXPECT_EQ(image.next_request_id(), 0);
    EXPECT_EQ(produce(image).hex.substr(4, 4), "0000");
    EXPECT_EQ(image.next_request_id(), 1);
}

TEST(ProducerRules, TimestampIsTheWallTimePassedIn) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    const auto hex = produce(image, WallTime{} + std::chrono::seconds{1} + 999999999ns).hex;
    EXPECT_EQ(hex.substr(24, 16), "01000000ffc99a3b");
}

TEST(ProducedImage, StagedWritesWaitForTheNextProduction) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(42, {{offset, Value{std::int64_t{300}}}})));
    EXPECT_EQ(image.pending(), 1u);
    EXPECT_EQ(data_hex(image), "00803b4501feff00");
    const auto produced = produce(image);
    EXPECT_EQ(produced.hex.substr(64), "00803b45012c0100");
    EXPECT_EQ(produced.carried, std::vector<std::uint64_t>{42});
    EXPECT_EQ(image.pending(), 0u);
    EXPECT_TRUE(produce(image).carried.empty());
}

TEST(ProducedImage, MultiTagBatchIsAppliedWholeInOneDatagram) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(7, {{speed_sp, Value{1.5F}},
                                      {start, Value{false}},
                                      {mode, Value{true}},
                                      {offset, Value{std::int64_t{-1}}}})));
    const auto produced = produce(image);
    // 1.5f = 0x3FC00000; byte 4: START cleared, MODE set.
    EXPECT_EQ(produced.hex.substr(64), "0000c03f02ffff00");
    EXPECT_EQ(produced.carried, std::vector<std::uint64_t>{7});
    EXPECT_EQ(data_hex(image), "0000c03f02ffff00");
}

TEST(ProducedImage, BatchesApplyInStagingOrder) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(1, {{offset, Value{std::int64_t{1}}}})));
    ASSERT_TRUE(image.stage(batch(2, {{offset, Value{std::int64_t{2}}}})));
    std::vector<std::uint64_t> carried{99};  // appended to, not cleared
    std::vector<std::byte> out(wire::max_datagram_size);
    image.produce(wall, out, carried);
    EXPECT_EQ(carried, (std::vector<std::uint64_t>{99, 1, 2}));
    EXPECT_EQ(data_hex(image), "00803b4501020000");
}

TEST(ProducedImage, BitWritesKeepTheOtherBitsOfTheirByte) {
    const auto plan = make_plan();
    const auto restored = from_hex("00000000a5000000");  // byte 4 = 1010 0101
    ProducedImage image(plan, restored);
    ASSERT_TRUE(image.stage(batch(1, {{mode, Value{true}}})));
    produce(image);
    EXPECT_EQ(data_hex(image), "00000000a7000000");
    ASSERT_TRUE(image.stage(batch(2, {{start, Value{false}}})));
    produce(image);
    EXPECT_EQ(data_hex(image), "00000000a6000000");
}

TEST(ProducedImage, DirtyOnlyWhenTheBytesChanged) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    produce(image);
    EXPECT_FALSE(image.dirty());
    ASSERT_TRUE(image.stage(batch(1, {{start, Value{true}}})));  // already set
    produce(image);
    EXPECT_FALSE(image.dirty());
    ASSERT_TRUE(image.stage(batch(2, {{start, Value{false}}})));
    produce(image);
    EXPECT_TRUE(image.dirty());
    produce(image);
    EXPECT_TRUE(image.dirty());  // until cleared
    image.clear_dirty();
    EXPECT_FALSE(image.dirty());
}

TEST(ProducedImage, StageFailsWhenTheQueueIsFull) {
    const auto plan = make_plan();
    ProducedImage image(plan, {}, 2);
    EXPECT_TRUE(image.stage(batch(1, {{start, Value{true}}})));
    EXPECT_TRUE(image.stage(batch(2, {{start, Value{true}}})));
    EXPECT_FALSE(image.stage(batch(3, {{start, Value{false}}})));
    EXPECT_EQ(image.pending(), 2u);
    const auto produced = produce(image);
    EXPECT_EQ(produced.carried, (std::vector<std::uint64_t>{1, 2}));
    EXPECT_EQ(data_hex(image), "00803b4501feff00");  // the rejected batch changed nothing
    EXPECT_TRUE(image.stage(batch(4, {{start, Value{false}}})));
}

TEST(ProducedImage, DiscardedBatchesAreNeverApplied) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(1, {{offset, Value{std::int64_t{1}}}})));
    produce(image);
    ASSERT_TRUE(image.stage(batch(2, {{offset, Value{std::int64_t{2}}}})));
    ASSERT_TRUE(image.stage(batch(3, {{start, Value{false}}})));
    std::vector<std::uint64_t> dropped{99};  // appended to, not cleared
    image.discard_pending(dropped);
    EXPECT_EQ(dropped, (std::vector<std::uint64_t>{99, 2, 3}));
    EXPECT_EQ(image.pending(), 0u);
    image.clear_dirty();
    const auto produced = produce(image);
    EXPECT_TRUE(produced.carried.empty());
    EXPECT_FALSE(image.dirty());
    EXPECT_EQ(data_hex(image), "00803b4501010000");  // batch 1 only
}

TEST(ProducedImage, TakenBatchesLeaveUnappliedWithWhatTheyWrite) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(2, {{offset, Value{std::int64_t{2}}}})));
    ASSERT_TRUE(image.stage(batch(3, {{start, Value{false}}})));
    std::vector<write::WriteBatch> taken(1);  // appended to, not cleared
    image.take_pending(taken);
    ASSERT_EQ(taken.size(), 3u);
    EXPECT_EQ(taken[1].id, 2u);
    EXPECT_EQ(taken[2].id, 3u);
    ASSERT_EQ(taken[1].writes.size(), 1u);
    EXPECT_EQ(taken[1].writes[0].value, Value{std::int64_t{2}});
    EXPECT_EQ(image.pending(), 0u);
    EXPECT_TRUE(produce(image).carried.empty());
    EXPECT_EQ(data_hex(image), "00803b4501feff00");
}

TEST(ProducedImage, ProjectionShowsEveryStagedBatchAndChangesNothing) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    std::vector<std::byte> projected{std::byte{0x55}};  // replaced, not appended to
    EXPECT_EQ(image.project(projected), 0u);            // nothing staged
    EXPECT_EQ(to_hex(projected), "00803b4501feff00");
    ASSERT_TRUE(image.stage(batch(3, {{offset, Value{std::int64_t{1}}}})));
    ASSERT_TRUE(image.stage(batch(4, {{mode, Value{true}}})));
    EXPECT_EQ(image.project(projected), 4u);
    EXPECT_EQ(to_hex(projected), "00803b4503010000");
    EXPECT_EQ(data_hex(image), "00803b4501feff00");
    EXPECT_EQ(image.pending(), 2u);
    EXPECT_FALSE(image.dirty());
}

TEST(ProducedImage, ProductionThroughAnIdLeavesTheLaterBatchesQueued) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(1, {{offset, Value{std::int64_t{1}}}})));
    ASSERT_TRUE(image.stage(batch(2, {{offset, Value{std::int64_t{2}}}})));
    std::vector<std::uint64_t> carried;
    std::vector<std::byte> out(wire::max_datagram_size);
    image.produce(wall, out, carried, 1);
    EXPECT_EQ(carried, std::vector<std::uint64_t>{1});
    EXPECT_EQ(data_hex(image), "00803b4501010000");
    EXPECT_EQ(image.pending(), 1u);
    image.produce(wall, out, carried, 0);  // nothing eligible
    EXPECT_EQ(image.pending(), 1u);
    image.produce(wall, out, carried);
    EXPECT_EQ(carried, (std::vector<std::uint64_t>{1, 2}));
    EXPECT_EQ(data_hex(image), "00803b4501020000");
}

TEST(ProducedImage, DiscardingARangeKeepsTheBatchesAroundIt) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    for (std::uint64_t id = 1; id <= 4; ++id) {
        ASSERT_TRUE(image.stage(batch(id, {{offset, Value{static_cast<std::int64_t>(id)}}})));
    }
    std::vector<std::uint64_t> dropped;
    image.discard_pending(1, 3, dropped);
    EXPECT_EQ(dropped, (std::vector<std::uint64_t>{2, 3}));
    const auto produced = produce(image);
    EXPECT_EQ(produced.carried, (std::vector<std::uint64_t>{1, 4}));
    EXPECT_EQ(data_hex(image), "00803b4501040000");
}

TEST(ProducedImage, AnAdoptedImageIsProducedNextWithTheStagedWritesOverIt) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    ASSERT_TRUE(image.stage(batch(1, {{offset, Value{std::int64_t{-1}}}})));
    EXPECT_TRUE(image.adopt(from_hex("1122334400000000")));
    EXPECT_EQ(data_hex(image), "1122334400000000");
    EXPECT_FALSE(image.dirty());
    EXPECT_EQ(image.pending(), 1u);
    // The same bytes again change nothing; another length is no image of this exchange.
    EXPECT_FALSE(image.adopt(from_hex("1122334400000000")));
    EXPECT_FALSE(image.adopt(from_hex("11223344")));
    EXPECT_EQ(produce(image).hex.substr(64), "1122334400ffff00");
}

TEST(ProducedImage, RequestIdsContinueAfterTheOneHeard) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});
    image.continue_after(41);
    EXPECT_EQ(image.next_request_id(), 42);
    EXPECT_EQ(produce(image).hex.substr(4, 4), "2a00");
    image.continue_after(65535);
    EXPECT_EQ(produce(image).hex.substr(4, 4), "0000");
    EXPECT_EQ(image.next_request_id(), 1);
}

TEST(ProducedImage, HoldsAWriteWhoseEveryValueIsThereAlreadyAndChangesNothingAsking) {
    const auto plan = make_plan();
    ProducedImage image(plan, {});  // SPEED_SP 3000, START on, MODE off, OFFSET -2
    const auto before = data_hex(image);
    const std::vector<write::TagWrite> held{{speed_sp, Value{std::int64_t{3000}}},
                                            {start, Value{true}}};
    EXPECT_TRUE(image.holds(held));
    const std::vector<write::TagWrite> half{{start, Value{true}}, {mode, Value{true}}};
    EXPECT_FALSE(image.holds(half));
    EXPECT_FALSE(image.holds(std::vector<write::TagWrite>{{offset, Value{std::int64_t{7}}}}));
    EXPECT_EQ(data_hex(image), before);
    EXPECT_FALSE(image.dirty());
    // Staged writes are not the image yet.
    ASSERT_TRUE(image.stage(batch(1, {{mode, Value{true}}})));
    EXPECT_FALSE(image.holds(std::vector<write::TagWrite>{{mode, Value{true}}}));
    produce(image);
    EXPECT_TRUE(image.holds(std::vector<write::TagWrite>{{mode, Value{true}}}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
