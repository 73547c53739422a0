// The role changes of a wired Pair, driven by a fake clock and a fake broker (its connection):
// the claim after the takeover and the lead once the claim is heard back, the fence of the
// sender threads (may_send) opening and closing with the lease, the order of a takeover (fence,
// images, republish, then the Sparkplug session with the bdSeq heard), the step-down on a newer
// epoch of the other unit, a lease that lapses by the clock alone, and the left writes a new
// leader answers again as the old leader's image lists them. The pair's parts are real
// (the exchanges module on loopback with one produced exchange, a JSON tree over a recording
// publisher); the loop never runs. With T = 2000 ms and R = 500 ms (core/redundancy/lease.hpp):
// a standby claims T - R after it last heard a record, its claim stands R after it was sent, and
// a leader is fenced T - 3R / 2 after it sent its newest acknowledged renewal.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/exchanges/exchanges_module.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "eip2mqtt/app/redundancy/image_message.hpp"
#include "eip2mqtt/app/redundancy/leader_record.hpp"
#include "eip2mqtt/app/redundancy/pair.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/redundancy/answer_key.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/fake_pair_connection.hpp"
#include "tests/support/fakes/recording_publisher.hpp"
#include "tests/support/fakes/tag_message.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::redundancy::LeaderRecord;

const std::string pair_leader_topic = "acme/_gateway/_pair/turbine/leader";
const std::string unit_role_topic = "acme/_gateway/gw-a/role";
const std::string image_prefix = "acme/_gateway/_pair/turbine/image/";
constexpr auto takeover = 2000ms;
constexpr auto claim_after = 1500ms;   // T - R
constexpr auto renewal = 500ms;        // R
constexpr auto fenced_after = 1250ms;  // T - 3R / 2

/// A publication only the role's holder says (retained).
adapters::mqtt::Message any_message() { return test::tag_message(true); }

class PairRoleTest : public ::testing::Test {
protected:
    PairRoleTest()
        : dir_(std::filesystem::temp_directory_path() /
               ("eip2mqtt_pair_role_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()))) {
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
        config_.gateway.id = "gw-a";
        config_.gateway.state_dir = (dir_ / "state").string();
        config_.mqtt.base_topic = "acme";
        config_.eip.bind = "127.0.0.1";
        config_.eip.port = 0;
        config_.redundancy.pair = "turbine";
        config_.redundancy.takeover = takeover;
    }
    ~PairRoleTest() override {
        south_.reset();
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }

    /// The pair wired to its parts (one produced exchange running), started and connected.
    void SetUp() override {
        south_ = std::make_unique<ExchangesModule>(config_, loop_.get_executor(), clock_,
                                                   pair_.exchanges_options());
        tree_ = std::make_unique<northbound::json_tree::JsonTree>(
            northbound::json_tree::json_tree_options(config_), tree_publisher_, south_->writes());
        SessionHooks session{
            [this](std::optional<std::uint8_t> heard) { on_open(heard); },
            [this] { on_end(); },
            [this] { return open_bd_seq_; },
        };
        pair_.wire({config_, [] { return std::uint64_t{0}; }, *tree_, south_->writes(),
                    south_->exchanges(), south_->north(), std::move(session),
                    [this] { on_republish(); }});
        south_->north().add(*tree_);  // learns the exchange: it takes writes to its tags
        south_->apply_plans({test::test_produced_plan()});
        ASSERT_NE(connection_, nullptr);
        pair_.start();
        ASSERT_TRUE(connection_->started);
        connection_->connect();
    }

    void on_open(std::optional<std::uint8_t> heard) {
        events_.push_back("open");
        opened_with_.push_back(heard);
        open_bd_seq_ = 41;
    }
    void on_end() {
        events_.push_back(fence_(any_message()) ? "end, fence open" : "end");
        open_bd_seq_.reset();
    }
    void on_republish() {
        events_.push_back(std::string("republish") + (fence_(any_message()) ? ", fence open" : "") +
                          ", images " + std::to_string(connection_->count_under(image_prefix)));
    }

    void advance(std::chrono::milliseconds by) {
        clock_.advance(by);
        pair_.tick(clock_.monotonic());
    }
    /// The last record the pair published on the leader topic.
    const adapters::mqtt::Message& last_record() const {
        for (auto it = connection_->published.rbegin(); it != connection_->published.rend(); ++it)
            if (it->topic == pair_leader_topic) return *it;
        throw std::logic_error("nothing published on the leader topic");
    }
    std::size_t records() const { return connection_->on(pair_leader_topic).size(); }
    /// The broker acknowledges the pair's last record and sends it back to it.
    void acknowledge_and_echo_last() {
        const auto record = last_record();
        connection_->acknowledge(record.ack_token);
        connection_->deliver({record.topic, record.payload});
    }
    /// The other unit's record, heard now.
    void hear_other(LeaderRecord record) {
        connection_->deliver({pair_leader_topic, encode_leader_record(record, takeover)});
    }
    /// From the start: the claim after the takeover, acknowledged, heard back; leads R later.
    void take_the_lead() {
        advance(claim_after);
        acknowledge_and_echo_last();
        advance(renewal);
        ASSERT_TRUE(pair_.leads());
    }

    test::FakeClock clock_;
    std::filesystem::path dir_;
    core::config::Config config_;
    boost::asio::io_context loop_;
    test::FakePairConnection* connection_ = nullptr;
    Pair pair_{clock_, [this](const core::config::Config&, adapters::mqtt::Message will) {
                   EXPECT_EQ(will.topic, pair_leader_topic);
                   auto connection = std::make_unique<test::FakePairConnection>();
                   connection_ = connection.get();
                   return connection;
               }};
    /// Fences every publication: open only while the pair leads.
    std::function<bool(const adapters::mqtt::Message&)> fence_ = pair_.may_send(nullptr);
    std::unique_ptr<ExchangesModule> south_;
    test::RecordingPublisher tree_publisher_;
    std::unique_ptr<northbound::json_tree::JsonTree> tree_;
    std::vector<std::string> events_;
    std::vector<std::optional<std::uint8_t>> opened_with_;
    std::optional<std::uint8_t> open_bd_seq_;
};

TEST_F(PairRoleTest, ItSubscribesAndSaysStandbyOnConnect) {
    EXPECT_EQ(connection_->subscriptions,
              (std::vector<std::string>{pair_leader_topic, image_prefix + "#"}));
    EXPECT_EQ(connection_->on(unit_role_topic), std::vector<std::string>{"standby"});
    EXPECT_FALSE(pair_.leads());
    EXPECT_FALSE(fence_(any_message()));
}

TEST_F(PairRoleTest, NoOtherLeaderItClaimsAfterTheTakeoverAndLeadsOnceItsClaimIsHeardBack) {
    advance(claim_after - 1ms);
    EXPECT_EQ(records(), 0u);
    advance(1ms);
    ASSERT_EQ(records(), 1u);
    const auto claim = decode_leader_record(last_record().payload);
    ASSERT_TRUE(claim.has_value());
    EXPECT_TRUE(claim->claim);
    EXPECT_EQ(claim->id, "gw-a");
    EXPECT_EQ(claim->epoch, 1u);

    // Acknowledged, but not heard back: the claim does not stand, the fence stays shut.
    connection_->acknowledge(last_record().ack_token);
    advance(renewal);
    EXPECT_FALSE(pair_.leads());
    EXPECT_FALSE(pair_.may_produce(clock_.monotonic()));
    EXPECT_FALSE(fence_(any_message()));
    EXPECT_TRUE(events_.empty());

    connection_->deliver({pair_leader_topic, connection_->on(pair_leader_topic).front()});
    advance(1ms);
    EXPECT_TRUE(pair_.leads());
    EXPECT_TRUE(pair_.may_produce(clock_.monotonic()));
    EXPECT_TRUE(fence_(any_message()));
    EXPECT_FALSE(pair_.follows_produced(clock_.monotonic()));
    EXPECT_EQ(connection_->on(unit_role_topic), (std::vector<std::string>{"standby", "leader"}));
}

TEST_F(PairRoleTest, NoClaimWhileItsConnectionIsDown) {
    connection_->up = false;
    advance(claim_after);
    advance(takeover);
    EXPECT_EQ(records(), 0u);
    connection_->connect();
    advance(0ms);  // the tick that sees it up: the claim waits T - R from there
    advance(claim_after - 1ms);
    EXPECT_EQ(records(), 0u);
    advance(1ms);
    EXPECT_EQ(records(), 1u);
}

TEST_F(PairRoleTest, TakingTheLeadOpensTheFenceThenPublishesImagesRepublishesAndOpensTheSession) {
    // The other unit led under epoch 3 with a Sparkplug session of bdSeq 40, then went silent.
    LeaderRecord other{"gw-b", 3, 0};
    other.bd_seq = 40;
    hear_other(other);
    EXPECT_TRUE(pair_.follows_produced(clock_.monotonic()));
    advance(claim_after);
    ASSERT_EQ(records(), 1u);
    EXPECT_EQ(decode_leader_record(last_record().payload)->epoch, 4u);
    acknowledge_and_echo_last();
    advance(renewal);
    ASSERT_TRUE(pair_.leads());
    EXPECT_EQ(events_, (std::vector<std::string>{"republish, fence open, images 1", "open"}));
    EXPECT_EQ(opened_with_, std::vector<std::optional<std::uint8_t>>{40});

    // Leading on, renewed: neither the republish nor the session again.
    for (int i = 0; i < 4; ++i) {
        acknowledge_and_echo_last();
        advance(renewal);
    }
    EXPECT_TRUE(pair_.leads());
    EXPECT_EQ(events_.size(), 2u);
    // Its renewals carry the open session's bdSeq.
    EXPECT_EQ(decode_leader_record(last_record().payload)->bd_seq, 41);
}

TEST_F(PairRoleTest, ANewerEpochOfTheOtherUnitStepsItDownAndShutsTheFenceAtOnce) {
    take_the_lead();
    acknowledge_and_echo_last();
    ASSERT_TRUE(fence_(any_message()));
    events_.clear();
    hear_other({"gw-b", 2, 0});  // a renewal: the other unit leads under a newer epoch
    // No tick: the fence shut as the record was read, before the session ended.
    EXPECT_FALSE(fence_(any_message()));
    EXPECT_FALSE(pair_.leads());
    EXPECT_FALSE(pair_.may_produce(clock_.monotonic()));
    EXPECT_TRUE(pair_.follows_produced(clock_.monotonic()));
    EXPECT_EQ(events_, std::vector<std::string>{"end"});
    EXPECT_EQ(connection_->on(unit_role_topic),
              (std::vector<std::string>{"standby", "leader", "standby"}));
    // Standing by, it neither claims nor renews while the other unit renews.
    const auto before = records();
    for (int i = 0; i < 8; ++i) {
        advance(renewal);
        hear_other({"gw-b", 2, 0});
    }
    EXPECT_EQ(records(), before);
    EXPECT_EQ(events_.size(), 1u);
}

TEST_F(PairRoleTest, ALeaseNotRenewedLapsesByTheClockAlone) {
    take_the_lead();
    const auto renewed_at = clock_.monotonic();  // the first renewal was sent on that tick
    acknowledge_and_echo_last();
    events_.clear();
    // Its renewals go unacknowledged from now on; no tick, no event: only time passes.
    clock_.advance(fenced_after - 1ms);
    EXPECT_TRUE(fence_(any_message()));
    EXPECT_TRUE(pair_.leads());
    clock_.advance(1ms);
    EXPECT_EQ(clock_.monotonic(), renewed_at + fenced_after);
    EXPECT_FALSE(fence_(any_message()));
    EXPECT_FALSE(pair_.leads());
    EXPECT_FALSE(pair_.may_produce(clock_.monotonic()));
    EXPECT_TRUE(events_.empty()) << "the session ends on the loop's next tick";
    advance(0ms);
    EXPECT_EQ(events_, std::vector<std::string>{"end"});
    EXPECT_EQ(connection_->on(unit_role_topic).back(), "standby");
}

TEST_F(PairRoleTest, ImagesArePublishedByTheLeaderUnderItsEpochNotByAStandby) {
    hear_other({"gw-b", 3, 0});
    advance(renewal);
    hear_other({"gw-b", 3, 0});
    EXPECT_EQ(connection_->count_under(image_prefix), 0u);

    advance(claim_after);
    acknowledge_and_echo_last();
    advance(renewal);
    ASSERT_TRUE(pair_.leads());
    ASSERT_EQ(connection_->count_under(image_prefix), 1u);
    const auto& producer = *south_->exchanges().producers().front();
    pair_.image_changed(producer);
    ASSERT_EQ(connection_->count_under(image_prefix), 2u);
    for (const auto& message : connection_->published) {
        if (message.topic.rfind(image_prefix, 0) != 0) continue;
        EXPECT_EQ(message.topic, image_prefix + "sp");
        const auto image = decode_image_message(message.payload);
        ASSERT_TRUE(image.has_value());
        EXPECT_EQ(image->id, "gw-a");
        EXPECT_EQ(image->epoch, 4u);
    }
}

TEST_F(PairRoleTest, TakingTheLeadItAnswersAgainTheLeftWritesTheOldLeadersImageListsUnheard) {
    // The other unit leads; two writes come, left to it; its image lists the first answered
    // `ok` and the second refused, and it dies before either answer leaves.
    hear_other({"gw-b", 3, 0});
    tree_->on_message({"acme/sp/VALUE/set", "5", false, "client/replies", "w1", -1});
    tree_->on_message({"acme/sp/VALUE/set", "6", false, "client/replies", "w2", -1});
    const auto& producer = *south_->exchanges().producers().front();
    core::redundancy::ImageMessage image{
        "gw-b", 3, adapters::state::layout_fingerprint(producer.plan()),
        std::vector<std::byte>(producer.plan().length, std::byte{0})};
    image.answers = {core::redundancy::answer_key("client/replies", "w1"),
                     core::redundancy::answer_key("client/replies", "w2")};
    image.refused = std::vector<std::uint64_t>{image.answers[1]};
    connection_->deliver({image_prefix + "sp", encode_image_message(image)});
    EXPECT_TRUE(tree_publisher_.on("client/replies").empty());

    advance(claim_after);
    acknowledge_and_echo_last();
    advance(renewal);
    ASSERT_TRUE(pair_.leads());
    std::vector<std::pair<std::string, std::string>> answers;
    for (const auto& m : tree_publisher_.published) {
        if (m.topic == "client/replies") answers.emplace_back(m.correlation_data, m.payload);
    }
    EXPECT_EQ(answers, (std::vector<std::pair<std::string, std::string>>{
                           {"w1", R"({"ok":true})"}, {"w2", R"({"error":"standby","ok":false})"}}));
}

TEST_F(PairRoleTest, ItsStatusSaysItsRoleEpochAndWhatIsLeftOfItsLease) {
    auto shown = nlohmann::json::parse(pair_.status_json());
    EXPECT_EQ(shown, nlohmann::json::parse(
                         R"({"pair":"turbine","role":"standby","epoch":0,"lease_left_ms":null})"));
    take_the_lead();
    acknowledge_and_echo_last();  // the renewal sent as it took the lead: fenced T - 3R/2 on
    shown = nlohmann::json::parse(pair_.status_json());
    EXPECT_EQ(shown["role"], "leader");
    EXPECT_EQ(shown["epoch"], 1);
    EXPECT_EQ(shown["lease_left_ms"], fenced_after.count());
    hear_other({"gw-b", 2, 0});
    shown = nlohmann::json::parse(pair_.status_json());
    EXPECT_EQ(shown["role"], "standby");
    EXPECT_EQ(shown["epoch"], 2);
    EXPECT_TRUE(shown["lease_left_ms"].is_null());
}

TEST_F(PairRoleTest, StopStopsItsConnection) {
    pair_.stop(3s);
    EXPECT_EQ(connection_->stopped, 3s);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
