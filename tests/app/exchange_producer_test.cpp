// ExchangeProducer's write results around a reload: a write carried by a sent datagram is
// answered ok once its save is delivered; a write still queued when the exchange is stopped for
// good is answered "reloaded"; none is left without a result, none gets two.
//
// The producer is driven by hand (produce, on_sent, the persister's flush): the loop never runs,
// so the scheduler's timer never fires and nothing depends on time.

#include "eip2mqtt/app/exchange_producer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/app/support/uns_json_recorder.hpp"

namespace eip2mqtt::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

core::plan::ExchangePlan make_plan() {
    core::plan::ExchangeSpec spec;
    spec.name = "sp";
    spec.direction = core::plan::Direction::produce;
    spec.exchange_id = 10;
    spec.destination = "127.0.0.1";
    spec.period = std::chrono::hours(1);
    spec.topic = "sp";
    core::plan::TagSpec value;
    value.name = "VALUE";
    value.address = {0, 0};
    value.type = core::plan::TagType::dint;
    value.writable = true;
    spec.tags = {value};
    return core::plan::make_exchange_plan(spec, "acme");
}

class ExchangeProducerTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_producer_" + std::string(info->name()) + "_" +
                                            std::to_string(::getpid()));
        fs::remove_all(dir_);
        store_ = std::make_unique<adapters::state::ImageStore>(dir_.string());
        adapters::udp::SenderOptions sender_options;
        sender_options.bind = "127.0.0.1";
        sender_ = std::make_unique<adapters::udp::Sender>(loop_.get_executor(), sender_options);
        scheduler_ = std::make_unique<ProducerScheduler>(loop_.get_executor(), *sender_);
        persister_ =
            std::make_unique<adapters::state::ImagePersister>(*store_, loop_.get_executor());
        producer_ =
            std::make_unique<ExchangeProducer>(make_plan(), adapters::udp::Endpoint{0x7F000001, 9},
                                               *scheduler_, *persister_, uns_.northbound());
        producer_->start(std::chrono::steady_clock::now(), 0, 1);
    }
    void TearDown() override {
        producer_.reset();
        persister_.reset();
        scheduler_.reset();
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
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
    test::UnsJsonRecorder uns_;
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

}  // namespace
}  // namespace eip2mqtt::app
