// SaveThenAnswer: every transition of a produced exchange's saves and write answers, driven by
// hand with a real ProducedImage (one DINT, VALUE at byte 0): a save that succeeds, one that
// fails, writes sent while a save is under way, saves ahead of production while saves fail,
// the retry once a second, and the writes a queued write's removal must take out of the file.

#include "eip2mqtt/core/exchange/save_then_answer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using Ids = std::vector<std::uint64_t>;

plan::ExchangePlan make_plan() {
    plan::ExchangePlan plan;
    plan.spec.name = "setpoints";
    plan.spec.direction = plan::Direction::produce;
    plan.spec.exchange_id = 7;
    plan.length = 4;
    plan::TagPlan tag;
    tag.spec.name = "VALUE";
    tag.spec.address = *plan::parse_address("0");
    tag.spec.type = plan::TagType::dint;
    tag.spec.writable = true;
    plan.tags = {tag};
    return plan;
}

std::int64_t value_in(std::span<const std::byte> data) {
    return std::get<std::int64_t>(plan::decode_value(data, plan::TagType::dint, {0, 0}));
}

const MonoTime t0 = MonoTime{} + 1000s;

class SaveThenAnswerTest : public ::testing::Test {
protected:
    /// Stages write `id`: VALUE = value.
    void stage(std::uint64_t id, std::int64_t value) {
        ASSERT_TRUE(image_.stage({id, {{0, plan::Value{value}}}}));
    }

    /// Asks for a save; the value the save writes, nullopt when none starts.
    std::optional<std::int64_t> request() {
        const auto bytes = machine_.request(image_);
        if (!bytes) return std::nullopt;
        return value_in(*bytes);
    }

    /// Produces a datagram as the producer does, and reports it sent: the carried writes, and
    /// what on_sent() says of them.
    struct Production {
        Ids carried;
        Ids answer;
        bool save = false;
        std::int64_t value = 0;  ///< VALUE in the datagram
    };
    Production produce() {
        Production production;
        std::vector<std::byte> out(wire::header_size + 4);
        image_.produce(WallTime{}, out, production.carried, machine_.produce_through());
        production.value = value_in(std::span(out).subspan(wire::header_size));
        const bool changed = image_.dirty();
        image_.clear_dirty();
        const auto sent = machine_.on_sent(production.carried, changed);
        production.answer.assign(sent.answer.begin(), sent.answer.end());
        production.save = sent.save;
        return production;
    }

    const plan::ExchangePlan plan_ = make_plan();
    ProducedImage image_{plan_, {}};
    SaveThenAnswer machine_{true};
};

TEST_F(SaveThenAnswerTest, AFileThatHoldsTheImageAsksForNoSave) {
    EXPECT_TRUE(machine_.saved());
    EXPECT_FALSE(machine_.saving());
    EXPECT_FALSE(machine_.on_staged());
    EXPECT_EQ(machine_.produce_through(), ProducedImage::no_limit);
    EXPECT_TRUE(machine_.error().empty());
    const auto production = produce();
    EXPECT_TRUE(production.carried.empty());
    EXPECT_FALSE(production.save);
    EXPECT_FALSE(machine_.on_tick(t0));
    EXPECT_FALSE(machine_.on_tick(t0 + 1h));
}

TEST_F(SaveThenAnswerTest, AnUnsavedImageIsSavedFirstAndItsSuccessIsAStatusChange) {
    SaveThenAnswer machine(false);
    EXPECT_FALSE(machine.saved());
    EXPECT_TRUE(machine.on_staged());
    EXPECT_EQ(machine.produce_through(), 0u);
    ASSERT_TRUE(machine.request(image_).has_value());
    EXPECT_TRUE(machine.saving());
    const auto saved = machine.on_saved(std::nullopt);
    EXPECT_TRUE(saved.answered.empty());
    EXPECT_TRUE(saved.status_changed);
    EXPECT_FALSE(saved.recovered);
    EXPECT_FALSE(machine.again());
    EXPECT_TRUE(machine.saved());
    EXPECT_FALSE(machine.saving());
}

TEST_F(SaveThenAnswerTest, AWriteIsProducedFirstAndAnsweredOnceItsSaveSucceeds) {
    stage(1, 42);
    EXPECT_FALSE(machine_.on_staged());  // produced before it is saved
    const auto production = produce();
    EXPECT_EQ(production.value, 42);
    EXPECT_EQ(production.carried, Ids{1});
    EXPECT_TRUE(production.answer.empty());
    EXPECT_TRUE(production.save);
    EXPECT_EQ(request(), 42);
    EXPECT_TRUE(machine_.saving());
    const auto saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{1});
    EXPECT_FALSE(saved.status_changed);
    EXPECT_FALSE(machine_.again());
    EXPECT_EQ(saved.refuse_after, saved.refuse_through);
}

TEST_F(SaveThenAnswerTest, AWriteThatChangesNothingIsAnsweredAtOnceWhenNoSaveIsUnderWay) {
    stage(1, 0);  // VALUE is 0 already
    const auto production = produce();
    EXPECT_EQ(production.carried, Ids{1});
    EXPECT_EQ(production.answer, Ids{1});
    EXPECT_FALSE(production.save);
}

TEST_F(SaveThenAnswerTest, AWriteThatChangesNothingWaitsForTheSaveAfterTheOneUnderWay) {
    stage(1, 5);
    ASSERT_TRUE(produce().save);
    ASSERT_EQ(request(), 5);
    stage(2, 5);  // the value of write 1: no byte changes
    const auto production = produce();
    EXPECT_EQ(production.carried, Ids{2});
    EXPECT_TRUE(production.answer.empty());
    EXPECT_TRUE(production.save);
    EXPECT_EQ(request(), std::nullopt);  // one is under way: it follows
    auto saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{1});
    EXPECT_TRUE(machine_.again());
    EXPECT_EQ(request(), 5);
    saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{2});
    EXPECT_FALSE(machine_.again());
}

TEST_F(SaveThenAnswerTest, ANewerWriteSentWhileASaveIsUnderWayWaitsForTheNextSave) {
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    ASSERT_EQ(request(), 10);
    stage(2, 20);
    const auto second = produce();
    EXPECT_EQ(second.value, 20);  // produced: saves succeed
    EXPECT_TRUE(second.answer.empty());
    ASSERT_TRUE(second.save);
    EXPECT_EQ(request(), std::nullopt);
    stage(3, 30);  // staged, not produced yet: held by the next save all the same
    auto saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{1});
    ASSERT_TRUE(machine_.again());
    EXPECT_EQ(request(), 30);
    saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{2});
    EXPECT_FALSE(machine_.again());
    // Write 3 was saved ahead of its production: answered as soon as it is sent.
    EXPECT_TRUE(machine_.holds(3));
    const auto third = produce();
    EXPECT_EQ(third.carried, Ids{3});
    EXPECT_EQ(third.answer, Ids{3});
    EXPECT_TRUE(third.save);  // the image changed: saved again, nothing waits for it
}

TEST_F(SaveThenAnswerTest, AFailedSaveAnswersItsSentWritesUnsavedAndRefusesTheQueuedOnes) {
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    stage(2, 20);  // queued, held by the save
    ASSERT_EQ(request(), 20);
    const auto saved = machine_.on_saved("disk full");
    EXPECT_EQ(saved.answered, Ids{1});
    EXPECT_EQ(saved.refuse_after, 0u);
    EXPECT_EQ(saved.refuse_through, 2u);
    EXPECT_TRUE(saved.status_changed);
    EXPECT_FALSE(saved.recovered);
    EXPECT_FALSE(machine_.again());
    EXPECT_FALSE(machine_.saved());
    EXPECT_EQ(machine_.error(), "disk full");
    EXPECT_EQ(machine_.produce_through(), 0u);  // nothing unsaved is produced now
}

TEST_F(SaveThenAnswerTest, WhileSavesFailAWriteIsSavedBeforeItIsProduced) {
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    ASSERT_EQ(request(), 10);
    machine_.on_saved("disk full");

    stage(2, 20);
    EXPECT_TRUE(machine_.on_staged());
    auto production = produce();
    EXPECT_EQ(production.value, 10);  // write 2 waits for its save
    EXPECT_TRUE(production.carried.empty());
    EXPECT_EQ(request(), 20);
    const auto saved = machine_.on_saved(std::nullopt);
    EXPECT_TRUE(saved.answered.empty());  // write 2 is answered once sent
    EXPECT_TRUE(saved.status_changed);
    EXPECT_TRUE(saved.recovered);
    EXPECT_TRUE(machine_.saved());
    EXPECT_TRUE(machine_.error().empty());
    production = produce();
    EXPECT_EQ(production.value, 20);
    EXPECT_EQ(production.answer, Ids{2});
}

TEST_F(SaveThenAnswerTest, AWriteSavedAheadFailsWithItsSaveAndOnlyTheWritesItHeldAreRefused) {
    SaveThenAnswer machine(false);
    stage(1, 10);
    ASSERT_TRUE(machine.request(image_).has_value());
    auto saved = machine.on_saved("disk full");
    EXPECT_EQ(saved.refuse_after, 0u);
    EXPECT_EQ(saved.refuse_through, 1u);
    image_.discard_pending(saved.refuse_after, saved.refuse_through, saved.answered);
    stage(2, 20);
    ASSERT_TRUE(machine.request(image_).has_value());
    saved = machine.on_saved(std::nullopt);
    stage(3, 30);
    ASSERT_TRUE(machine.request(image_).has_value());
    stage(4, 40);  // staged after the save started: not held by it
    saved = machine.on_saved("read-only file system");
    EXPECT_EQ(saved.refuse_after, 2u);
    EXPECT_EQ(saved.refuse_through, 3u);
    EXPECT_TRUE(saved.status_changed);  // saved() changed
    EXPECT_EQ(machine.error(), "read-only file system");
    EXPECT_EQ(machine.produce_through(), 2u);
    EXPECT_TRUE(machine.holds(2));
    EXPECT_FALSE(machine.holds(3));
}

TEST_F(SaveThenAnswerTest, AWriteSavedAheadIsAnsweredWhenSentWhileSavesFailAgain) {
    SaveThenAnswer machine(false);
    stage(1, 10);
    ASSERT_TRUE(machine.request(image_).has_value());
    machine.on_saved(std::nullopt);                    // write 1 saved ahead
    ASSERT_TRUE(machine.request(image_).has_value());  // e.g. a followed image
    const auto saved = machine.on_saved("disk full");
    EXPECT_EQ(saved.refuse_after, saved.refuse_through);  // write 1 is on disk
    Ids carried;
    std::vector<std::byte> out(wire::header_size + 4);
    image_.produce(WallTime{}, out, carried, machine.produce_through());
    EXPECT_EQ(carried, Ids{1});
    ASSERT_TRUE(image_.dirty());
    // The image changed, but the file holds it: no save is asked for.
    const auto sent = machine.on_sent(carried, true);
    EXPECT_EQ(Ids(sent.answer.begin(), sent.answer.end()), Ids{1});
    EXPECT_FALSE(sent.save);
    // A later save of nothing staged forgets no write the file holds.
    ASSERT_TRUE(machine.request(image_).has_value());
    machine.on_saved(std::nullopt);
    EXPECT_TRUE(machine.holds(1));
    EXPECT_FALSE(machine.holds(2));
}

TEST_F(SaveThenAnswerTest, AWriteSentBeforeTheSaveThatFollowsAnotherStartsWaitsForIt) {
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    ASSERT_EQ(request(), 10);
    ASSERT_EQ(request(), std::nullopt);
    machine_.on_saved(std::nullopt);
    ASSERT_TRUE(machine_.again());
    stage(2, 10);  // changes nothing, sent before the next save starts
    const auto production = produce();
    EXPECT_EQ(production.carried, Ids{2});
    EXPECT_TRUE(production.answer.empty());
    EXPECT_TRUE(production.save);
    EXPECT_EQ(request(), 10);
    EXPECT_EQ(machine_.on_saved(std::nullopt).answered, Ids{2});
}

TEST_F(SaveThenAnswerTest, ARepeatedErrorIsNoStatusChangeAnotherErrorIs) {
    SaveThenAnswer machine(false);
    ASSERT_TRUE(machine.request(image_).has_value());
    EXPECT_TRUE(machine.on_saved("disk full").status_changed);
    ASSERT_TRUE(machine.request(image_).has_value());
    EXPECT_FALSE(machine.on_saved("disk full").status_changed);
    ASSERT_TRUE(machine.request(image_).has_value());
    EXPECT_TRUE(machine.on_saved("read-only file system").status_changed);
    ASSERT_TRUE(machine.request(image_).has_value());
    const auto saved = machine.on_saved(std::nullopt);
    EXPECT_TRUE(saved.status_changed);
    EXPECT_TRUE(saved.recovered);
}

TEST_F(SaveThenAnswerTest, ASaveAskedForDuringAFailingOneFollowsIt) {
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    stage(2, 20);  // queued, held by the save
    ASSERT_EQ(request(), 20);
    ASSERT_EQ(request(), std::nullopt);  // e.g. the pair's standby followed an image
    const auto saved = machine_.on_saved("disk full");
    EXPECT_TRUE(machine_.again());
    EXPECT_EQ(saved.refuse_through, 2u);
    Ids refused;
    image_.discard_pending(saved.refuse_after, saved.refuse_through, refused);
    EXPECT_EQ(refused, Ids{2});
    EXPECT_EQ(request(), 10);  // the refused write 2 is no longer in the image saved
}

TEST_F(SaveThenAnswerTest, WhileSavesFailTheImageIsSavedAgainEverySecond) {
    SaveThenAnswer machine(false);
    EXPECT_FALSE(machine.on_tick(t0));  // unsaved, none under way: the interval starts
    EXPECT_FALSE(machine.on_tick(t0 + 999ms));
    EXPECT_TRUE(machine.on_tick(t0 + 1s));
    ASSERT_TRUE(machine.request(image_).has_value());
    EXPECT_FALSE(machine.on_tick(t0 + 10s));  // under way
    machine.on_saved("disk full");
    EXPECT_FALSE(machine.on_tick(t0 + 10s));  // the interval starts
    EXPECT_FALSE(machine.on_tick(t0 + 10s + 999ms));
    EXPECT_TRUE(machine.on_tick(t0 + 11s));
    EXPECT_FALSE(machine.on_tick(t0 + 11s));  // once: the interval starts again
    EXPECT_TRUE(machine.on_tick(t0 + 12s));
    ASSERT_TRUE(machine.request(image_).has_value());
    machine.on_saved(std::nullopt);
    EXPECT_FALSE(machine.on_tick(t0 + 20s));
    EXPECT_FALSE(machine.on_tick(t0 + 30s));
}

TEST_F(SaveThenAnswerTest, AFailureRestartsTheRetryInterval) {
    SaveThenAnswer machine(false);
    ASSERT_TRUE(machine.request(image_).has_value());
    machine.on_saved("disk full");
    EXPECT_FALSE(machine.on_tick(t0));                 // retry due at t0 + 1 s
    ASSERT_TRUE(machine.request(image_).has_value());  // a write asked for a save
    machine.on_saved("disk full");
    EXPECT_FALSE(machine.on_tick(t0 + 1s));  // a new interval starts here
    EXPECT_FALSE(machine.on_tick(t0 + 1s + 999ms));
    EXPECT_TRUE(machine.on_tick(t0 + 2s));
}

TEST_F(SaveThenAnswerTest, WritesSavedAheadAndWritesNotYetSavedInOneDatagram) {
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    ASSERT_EQ(request(), 10);
    machine_.on_saved("disk full");
    stage(2, 20);
    ASSERT_TRUE(machine_.on_staged());
    ASSERT_EQ(request(), 20);
    stage(3, 30);
    ASSERT_TRUE(machine_.on_staged());
    ASSERT_EQ(request(), std::nullopt);
    auto saved = machine_.on_saved(std::nullopt);  // write 2 is on disk, 3 follows
    ASSERT_TRUE(machine_.again());
    ASSERT_EQ(request(), 30);
    // Saves succeed again: the next datagram carries 2 (saved ahead) and 3 (its save is under
    // way, and it waits for the one after, as any write sent during a save).
    const auto production = produce();
    EXPECT_EQ(production.carried, (Ids{2, 3}));
    EXPECT_EQ(production.answer, Ids{2});
    EXPECT_TRUE(production.save);
    EXPECT_EQ(request(), std::nullopt);
    saved = machine_.on_saved(std::nullopt);
    EXPECT_TRUE(saved.answered.empty());
    ASSERT_TRUE(machine_.again());
    EXPECT_EQ(request(), 30);
    saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{3});
}

TEST_F(SaveThenAnswerTest, SentWritesStillWaitForTheirSaveWhenTheQueueIsEmptied) {
    // A reload stops the exchange: queued writes are taken out, the sent ones keep waiting.
    stage(1, 10);
    ASSERT_TRUE(produce().save);
    ASSERT_EQ(request(), 10);
    stage(2, 20);
    Ids dropped;
    image_.discard_pending(dropped);
    EXPECT_EQ(dropped, Ids{2});
    EXPECT_FALSE(machine_.holds(2));  // never saved: the file needs no other save
    const auto saved = machine_.on_saved(std::nullopt);
    EXPECT_EQ(saved.answered, Ids{1});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
