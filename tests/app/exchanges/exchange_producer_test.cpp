// ExchangeProducer's write results around a reload: a write carried by a sent datagram is
// answered ok once its save is delivered; a write still queued when the exchange is stopped for
// good is answered "reloaded"; none is left without a result, none gets two. And around image
// saves that fail: never a plain ok for a write whose image is not saved, never a value
// produced that the file does not hold, bar the writes answered "saved":false.
//
// Saves fail for real: the state directory is replaced by a regular file after the image file
// was removed, so that the file cannot be created again (ENOTDIR), whoever runs the test.
//
// The producer is driven by hand (produce, on_sent, the persister's flush): the loop never runs,
// so the scheduler's timer never fires and nothing depends on time.

#include "eip2mqtt/app/exchanges/exchange_producer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/header.hpp"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/switched_role.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

class ExchangeProducerTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_producer_" + std::string(info->name()) + "_" +
                                            std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);  // the gateway's StateDirLock makes it
        store_ = std::make_unique<adapters::state::ImageStore>(dir_.string());
        adapters::udp::SenderOptions sender_options;
        sender_options.bind = "127.0.0.1";
        sender_ = std::make_unique<adapters::udp::Sender>(loop_.get_executor(), sender_options);
        scheduler_ = std::make_unique<ProducerScheduler>(loop_.get_executor(), *sender_);
        persister_ =
            std::make_unique<adapters::state::ImagePersister>(*store_, loop_.get_executor());
        producer_ = make_producer();
        producer_->start(std::chrono::steady_clock::now(), 0, 1);
        persister_->flush();  // the initial image is saved
    }
    void TearDown() override {
        producer_.reset();
        persister_.reset();
        scheduler_.reset();
        std::error_code ignored;
        fs::remove(dir_, ignored);  // when a test left a file in its place
        fs::remove_all(dir_, ignored);
    }

    std::unique_ptr<ExchangeProducer> make_producer(
        std::optional<ImageHandover> handover = std::nullopt) {
        return std::make_unique<ExchangeProducer>(
            test::test_produced_plan(), adapters::udp::Endpoint{0x7F000001, 9}, *scheduler_,
            *persister_, uns_.northbound(), totals_, std::move(handover));
    }

    /// Saves fail from now on: the image file is gone and cannot be created again.
    void break_the_disk() {
        fs::remove_all(dir_);
        std::ofstream(dir_.string()) << "not a directory";
    }
    void mend_the_disk() {
        fs::remove(dir_);
        fs::create_directories(dir_);
    }

    /// VALUE in the datagram the producer sends next.
    std::int64_t next_value() {
        const auto wall = std::chrono::system_clock::now();
        const auto bytes = producer_->produce(wall);
        producer_->on_sent(true, wall);
        const auto value = core::plan::decode_value(bytes.subspan(core::wire::header_size),
                                                    core::plan::TagType::dint, {0, 0});
        return std::get<std::int64_t>(value);
    }

    /// The image being produced, as the file would hold it.
    std::vector<std::byte> image_bytes() const {
        const auto data = producer_->image().data();
        return {data.begin(), data.end()};
    }

    /// The `_status` payloads published so far.
    std::vector<json> statuses() const {
        std::vector<json> all;
        for (const auto& payload : uns_.publisher.on("acme/sp/_status")) {
            all.push_back(json::parse(payload));
        }
        return all;
    }

    /// Stages `VALUE = value`, answered on `reply/{name}` with correlation data `name`.
    void write(const std::string& name, std::int64_t value) {
        const auto rejection =
            producer_->stage({{0, core::plan::Value{value}}}, {"reply/" + name, name},
                             std::chrono::steady_clock::now());
        ASSERT_FALSE(rejection.has_value()) << rejection->message;
    }

    /// One production, as the scheduler does it: build the datagram, then the bookkeeping.
    void produce_once() {
        const auto wall = std::chrono::system_clock::now();
        producer_->produce(wall);
        producer_->on_sent(true, wall);
    }

    /// The results published so far, by correlation data (every one of them, in order).
    std::map<std::string, std::vector<json>> results() const {
        std::map<std::string, std::vector<json>> by_name;
        for (const auto& m : uns_.publisher.published) {
            if (!m.topic.starts_with("reply/")) continue;
            EXPECT_EQ(m.topic, "reply/" + m.correlation_data);
            EXPECT_EQ(m.qos, 1);
            EXPECT_FALSE(m.retain);
            EXPECT_FALSE(m.coalesce);  // each result is delivered, never replaced by the next
            by_name[m.correlation_data].push_back(json::parse(m.payload));
        }
        return by_name;
    }

    fs::path dir_;
    boost::asio::io_context loop_;
    std::unique_ptr<adapters::state::ImageStore> store_;
    std::unique_ptr<adapters::udp::Sender> sender_;
    std::unique_ptr<ProducerScheduler> scheduler_;
    std::unique_ptr<adapters::state::ImagePersister> persister_;
    test::JsonTreeRecorder uns_;
    ImageSaveTotals totals_;
    std::unique_ptr<ExchangeProducer> producer_;
};

const json ok = {{"ok", true}};
const json reloaded = {{"ok", false}, {"error", "reloaded"}};

TEST_F(ExchangeProducerTest, QueuedWritesAreAnsweredReloadedOnceAndNeverApplied) {
    write("a", 5);
    write("b", 6);
    EXPECT_TRUE(results().empty());  // queued: no result until a datagram carries them

    producer_->stop();
    EXPECT_EQ(producer_->cancel_queued_writes("reloaded"), 2u);
    EXPECT_EQ(results(),
              (std::map<std::string, std::vector<json>>{{"a", {reloaded}}, {"b", {reloaded}}}));
    EXPECT_EQ(producer_->image().pending(), 0u);
    EXPECT_EQ(
        core::plan::decode_value(producer_->image().data(), core::plan::TagType::dint, {0, 0}),
        core::plan::Value{std::int64_t{0}});
    // Answered once: nothing is left to cancel, and no later save answers them again.
    EXPECT_EQ(producer_->cancel_queued_writes("reloaded"), 0u);
    persister_->flush();
    EXPECT_EQ(results().size(), 2u);
    EXPECT_EQ(results().at("a").size(), 1u);
}

TEST_F(ExchangeProducerTest, QueuedWritesLeftToAnotherUnitAreDroppedUnansweredNeverApplied) {
    write("a", 5);
    EXPECT_EQ(producer_->cancel_queued_writes(std::nullopt), 1u);
    produce_once();
    persister_->flush();
    EXPECT_TRUE(results().empty());
    EXPECT_EQ(
        core::plan::decode_value(producer_->image().data(), core::plan::TagType::dint, {0, 0}),
        core::plan::Value{std::int64_t{0}});
}

TEST_F(ExchangeProducerTest, QueuedWritesTakenForThePairAreUnansweredAndCarryWhatTheyWrote) {
    write("a", 5);
    write("b", 6);
    const auto taken = producer_->take_queued_writes();
    ASSERT_EQ(taken.size(), 2u);
    EXPECT_EQ(taken[0].reply.topic, "reply/a");
    EXPECT_EQ(taken[0].reply.correlation_data, "a");
    const auto* write = std::get_if<ExchangeWrite>(&taken[1].outcome);
    ASSERT_NE(write, nullptr);
    EXPECT_EQ(write->producer, &producer_->plan());
    ASSERT_EQ(write->writes.size(), 1u);
    EXPECT_EQ(write->writes[0].value, core::plan::Value{std::int64_t{6}});
    EXPECT_TRUE(producer_->take_queued_writes().empty());
    produce_once();
    persister_->flush();
    EXPECT_TRUE(results().empty());
    EXPECT_EQ(
        core::plan::decode_value(producer_->image().data(), core::plan::TagType::dint, {0, 0}),
        core::plan::Value{std::int64_t{0}});
}

TEST_F(ExchangeProducerTest, AnAnswerGateHoldsOkUntilItRunsTheAnswer) {
    std::vector<std::function<void()>> held;
    std::vector<std::uint64_t> gated;
    test::SwitchedRole role;
    role.on_answer = [&](const ExchangeProducer& producer, std::uint64_t write_id,
                         const WriteReply& reply, std::function<void()> answer) {
        EXPECT_EQ(&producer, producer_.get());
        EXPECT_EQ(reply.topic, "reply/a");
        gated.push_back(write_id);
        held.push_back(std::move(answer));
    };
    producer_->set_role(role);
    write("a", 5);
    produce_once();
    persister_->flush();
    ASSERT_EQ(held.size(), 1u);
    ASSERT_EQ(gated.size(), 1u);
    EXPECT_TRUE(results().empty());
    held[0]();
    EXPECT_EQ(results(), (std::map<std::string, std::vector<json>>{{"a", {ok}}}));
}

TEST_F(ExchangeProducerTest, ACarriedWriteWhoseSaveIsUnderWayStillGetsItsOkAfterTheFlush) {
    write("carried", 7);
    produce_once();  // sent; its save is under way, so no result yet
    EXPECT_TRUE(results().empty());
    write("queued", 8);

    // Gateway::apply_exchanges: flush the saves, then stop and cancel what is still queued.
    persister_->flush();
    producer_->stop();
    EXPECT_EQ(producer_->cancel_queued_writes("reloaded"), 1u);
    EXPECT_EQ(results(), (std::map<std::string, std::vector<json>>{{"carried", {ok}},
                                                                   {"queued", {reloaded}}}));
    // The saved image holds the carried write, not the cancelled one.
    const auto saved = store_->load(producer_->plan());
    ASSERT_TRUE(saved.has_value());
    EXPECT_EQ(core::plan::decode_value(*saved, core::plan::TagType::dint, {0, 0}),
              core::plan::Value{std::int64_t{7}});
}

TEST_F(ExchangeProducerTest, WithNothingQueuedNothingIsCancelled) {
    write("a", 1);
    produce_once();
    persister_->flush();
    producer_->stop();
    EXPECT_EQ(producer_->cancel_queued_writes("reloaded"), 0u);
    EXPECT_EQ(results(), (std::map<std::string, std::vector<json>>{{"a", {ok}}}));
}

TEST_F(ExchangeProducerTest, AWriteSentBeforeItsSaveFailedIsAnsweredSavedFalse) {
    EXPECT_TRUE(producer_->saved());
    break_the_disk();
    write("sent", 7);
    EXPECT_EQ(next_value(), 7);  // saves succeeded so far: produced first, saved after
    persister_->flush();
    const auto answer = results().at("sent");
    ASSERT_EQ(answer.size(), 1u);
    EXPECT_EQ(answer[0]["ok"], true);
    EXPECT_EQ(answer[0]["saved"], false);
    const auto expected_reason =
        "not saved: open " + (dir_ / "sp.image.tmp").string() + ": Not a directory";
    EXPECT_EQ(answer[0]["error"], expected_reason);
    EXPECT_EQ(test::schema_problem(test::schema_file("write-result.json"), answer[0].dump()), "");
    EXPECT_FALSE(producer_->saved());
    EXPECT_EQ(producer_->counters().save_failures, 1u);
    EXPECT_EQ(totals_.failures, 1u);
    EXPECT_EQ(totals_.writes_sent_unsaved, 1u);
    // `_status` says so at once.
    ASSERT_FALSE(statuses().empty());
    const auto status = statuses().back();
    EXPECT_EQ(status["saved"], false);
    EXPECT_EQ(status["save_failures"], 1);
    EXPECT_EQ(status["save_error"], expected_reason.substr(11));
    EXPECT_EQ(test::schema_problem(test::schema_file("status.json"), status.dump()), "");
}

TEST_F(ExchangeProducerTest, WhileSavesFailAWriteIsSavedBeforeItIsProducedOrRefused) {
    write("first", 7);
    EXPECT_EQ(next_value(), 7);
    persister_->flush();
    break_the_disk();
    write("sent", 8);
    EXPECT_EQ(next_value(), 8);
    persister_->flush();  // the first failure: "sent" was on the wire already
    write("refused", 9);
    EXPECT_EQ(next_value(), 8);  // not before its save
    persister_->flush();
    EXPECT_EQ(next_value(), 8);  // and never, since it failed
    const auto all = results();
    EXPECT_EQ(all.at("first"), std::vector<json>{ok});
    EXPECT_EQ(all.at("sent")[0]["saved"], false);
    ASSERT_EQ(all.at("refused").size(), 1u);
    EXPECT_EQ(all.at("refused")[0]["ok"], false);
    EXPECT_EQ(all.at("refused")[0]["error"],
              "not saved: open " + (dir_ / "sp.image.tmp").string() + ": Not a directory");
    EXPECT_EQ(totals_.writes_not_saved, 1u);
    EXPECT_EQ(producer_->image().pending(), 0u);

    // Room again: the next write is saved first, then produced and answered ok.
    mend_the_disk();
    write("after", 10);
    EXPECT_EQ(next_value(), 8);
    persister_->flush();
    EXPECT_TRUE(producer_->saved());
    EXPECT_EQ(next_value(), 10);
    EXPECT_EQ(results().at("after"), std::vector<json>{ok});
    EXPECT_EQ(store_->load(producer_->plan()).value(), image_bytes());
    EXPECT_EQ(statuses().back()["saved"], true);
    EXPECT_EQ(statuses().back()["save_error"], nullptr);
}

TEST_F(ExchangeProducerTest, AnUnsavedImageIsSavedAgainOnceASecondWithoutAWrite) {
    write("a", 5);
    EXPECT_EQ(next_value(), 5);
    break_the_disk();
    write("b", 6);
    EXPECT_EQ(next_value(), 6);
    persister_->flush();
    ASSERT_FALSE(producer_->saved());
    mend_the_disk();
    const auto now = std::chrono::steady_clock::now();
    producer_->on_tick(now);  // arms the retry
    persister_->flush();
    EXPECT_FALSE(producer_->saved());
    producer_->on_tick(now + 1s);
    persister_->flush();
    EXPECT_TRUE(producer_->saved());
    const auto saved = store_->load(producer_->plan());
    ASSERT_TRUE(saved.has_value());
    EXPECT_EQ(core::plan::decode_value(*saved, core::plan::TagType::dint, {0, 0}),
              core::plan::Value{std::int64_t{6}});
}

TEST_F(ExchangeProducerTest, AHandedOverImageGoesOnAndIsWrittenBackToItsFile) {
    write("a", 5);
    EXPECT_EQ(next_value(), 5);
    persister_->flush();
    fs::remove(store_->path_of(producer_->plan()));  // the file no longer holds it
    producer_->stop();
    auto next = make_producer(producer_->hand_over());
    producer_ = std::move(next);
    producer_->start(std::chrono::steady_clock::now(), 0, 1);
    EXPECT_EQ(next_value(), 5);
    persister_->flush();
    EXPECT_TRUE(producer_->saved());
    const auto saved = store_->load(producer_->plan());
    ASSERT_TRUE(saved.has_value());
    EXPECT_EQ(*saved, image_bytes());
}

TEST_F(ExchangeProducerTest, AQueuedWriteSavedAheadThenCancelledLeavesTheFile) {
    break_the_disk();
    write("a", 5);
    EXPECT_EQ(next_value(), 5);
    persister_->flush();  // failed: from now on, writes are saved ahead of their production
    ASSERT_FALSE(producer_->saved());
    mend_the_disk();
    write("b", 6);  // saved ahead, not produced yet
    persister_->flush();
    const auto ahead = store_->load(producer_->plan());
    ASSERT_TRUE(ahead.has_value());
    EXPECT_EQ(core::plan::decode_value(*ahead, core::plan::TagType::dint, {0, 0}),
              core::plan::Value{std::int64_t{6}});
    producer_->stop();
    EXPECT_EQ(producer_->cancel_queued_writes("reloaded"), 1u);
    persister_->flush();
    // Never produced: the file holds the produced image again.
    EXPECT_EQ(store_->load(producer_->plan()).value(), image_bytes());
    EXPECT_EQ(results().at("b"), std::vector<json>{reloaded});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
