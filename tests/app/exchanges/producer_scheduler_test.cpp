// ProducerScheduler without a socket: the batches go to a recording fake, and the scheduler reads
// a fake clock that stands at the moment the test began. Every deadline is set before that moment
// (so the real timer has expired too) or an hour after it, so what is due at a wake-up does not
// depend on how fast the machine is; the loop runs one handler at a time, bounded.

#include "eip2mqtt/app/exchanges/producer_scheduler.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_producible.hpp"
#include "tests/support/fakes/switched_role.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using test::RecordingProducible;

class ProducerSchedulerTest : public ::testing::Test {
protected:
    ProducerSchedulerTest() { clock_.set_monotonic(std::chrono::steady_clock::now()); }

    /// Runs the loop until the next batch has left (a wait the scheduler cancelled by arming
    /// again runs first, and sends nothing); false if none left within the bound.
    bool wake() {
        const auto before = batches_.size();
        const auto give_up = std::chrono::steady_clock::now() + 10s;
        while (batches_.size() == before && std::chrono::steady_clock::now() < give_up) {
            loop_.restart();
            loop_.run_one_for(1s);
        }
        return batches_.size() > before;
    }
    core::exchange::ProductionSchedule due_now(std::chrono::nanoseconds period = 1h) const {
        return {clock_.monotonic() - 10ms, period, 0, 1};
    }
    core::exchange::ProductionSchedule due_later() const {
        return {clock_.monotonic() + 1h, 1h, 0, 1};
    }

    test::FakeClock clock_;
    boost::asio::io_context loop_;
    std::vector<std::string> log_;
    std::vector<std::vector<std::uint16_t>> batches_;  ///< destination ports, per batch
    std::vector<bool> refuse_;                         ///< by position in the batch
    ProducerScheduler scheduler_{
        loop_.get_executor(),
        [this](std::span<const adapters::udp::OutgoingDatagram> batch, std::vector<bool>& sent) {
            log_.push_back("send_batch");
            batches_.emplace_back();
            sent.assign(batch.size(), true);
            for (std::size_t i = 0; i < batch.size(); ++i) {
                batches_.back().push_back(batch[i].to.port);
                EXPECT_EQ(batch[i].bytes.size(), 4u);
                if (i < refuse_.size() && refuse_[i]) sent[i] = false;
            }
        },
        clock_};
};

TEST_F(ProducerSchedulerTest, TheExchangesDueLeaveInOneBatchAndBookkeepingComesAfterIt) {
    RecordingProducible a("a", 1001, log_);
    RecordingProducible b("b", 1002, log_);
    RecordingProducible later("later", 1003, log_);
    const auto id_a = scheduler_.add(a, due_now());
    const auto id_b = scheduler_.add(b, due_now());
    const auto id_later = scheduler_.add(later, due_later());
    ASSERT_TRUE(wake());
    ASSERT_EQ(batches_.size(), 1u);
    EXPECT_EQ(batches_[0], (std::vector<std::uint16_t>{1001, 1002}));
    EXPECT_EQ(log_, (std::vector<std::string>{"produce a", "produce b", "send_batch", "sent a",
                                              "sent b"}));
    scheduler_.remove(id_a);
    scheduler_.remove(id_b);
    scheduler_.remove(id_later);
}

TEST_F(ProducerSchedulerTest, ADatagramTheSenderRefusesIsReportedToItsOwnExchangeOnly) {
    RecordingProducible a("a", 1001, log_);
    RecordingProducible b("b", 1002, log_);
    const auto id_a = scheduler_.add(a, due_now());
    const auto id_b = scheduler_.add(b, due_now());
    refuse_ = {true, false};
    ASSERT_TRUE(wake());
    EXPECT_EQ(log_, (std::vector<std::string>{"produce a", "produce b", "send_batch", "refused a",
                                              "sent b"}));
    scheduler_.remove(id_a);
    scheduler_.remove(id_b);
}

TEST_F(ProducerSchedulerTest, ARemovedExchangeIsNeverReachedAgain) {
    RecordingProducible a("a", 1001, log_);
    RecordingProducible b("b", 1002, log_);
    const auto id_a = scheduler_.add(a, due_now());
    const auto id_b = scheduler_.add(b, due_now());
    scheduler_.remove(id_b);
    ASSERT_TRUE(wake());
    EXPECT_EQ(log_, (std::vector<std::string>{"produce a", "send_batch", "sent a"}));
    scheduler_.remove(id_a);
}

TEST_F(ProducerSchedulerTest, DeadlinesTheLoopFellBehindOnAreCountedNotSentInABurst) {
    RecordingProducible a("a", 1001, log_);
    // First deadline two and a half periods ago: one datagram now, two deadlines skipped.
    const auto id = scheduler_.add(a, {clock_.monotonic() - 150min, 1h, 0, 1});
    ASSERT_TRUE(wake());
    EXPECT_EQ(log_, (std::vector<std::string>{"produce a", "send_batch", "sent a"}));
    EXPECT_EQ(a.skipped_, 2u);
    scheduler_.remove(id);
}

TEST_F(ProducerSchedulerTest, AnExchangeAddedWithAnEarlierDeadlineRearmsTheTimer) {
    RecordingProducible later("later", 1003, log_);
    RecordingProducible a("a", 1001, log_);
    const auto id_later = scheduler_.add(later, due_later());
    const auto id_a = scheduler_.add(a, due_now());
    ASSERT_TRUE(wake());
    EXPECT_EQ(log_, (std::vector<std::string>{"produce a", "send_batch", "sent a"}));
    scheduler_.remove(id_a);
    scheduler_.remove(id_later);
}

TEST_F(ProducerSchedulerTest, ADatagramCarriesTheUtcTimeOfItsDeadlineNotOfTheWakeUp) {
    RecordingProducible a("a", 1001, log_);
    const auto id = scheduler_.add(a, due_now());  // due 10 ms before the clock's time
    ASSERT_TRUE(wake());
    EXPECT_EQ(a.stamps_, std::vector<core::WallTime>{clock_.wall() - 10ms});
    scheduler_.remove(id);
}

TEST_F(ProducerSchedulerTest, AWallClockStepIsFollowedFromTheNextWakeUp) {
    RecordingProducible a("a", 1001, log_);
    RecordingProducible b("b", 1002, log_);
    const auto id_a = scheduler_.add(a, due_now());
    ASSERT_TRUE(wake());
    const auto before = clock_.wall();
    clock_.set_wall(before + 1h);  // beyond SamplingClock's tolerance: anchored again
    const auto id_b = scheduler_.add(b, due_now());
    ASSERT_TRUE(wake());
    EXPECT_EQ(a.stamps_, std::vector<core::WallTime>{before - 10ms});
    EXPECT_EQ(b.stamps_, std::vector<core::WallTime>{before + 1h - 10ms});
    scheduler_.remove(id_a);
    scheduler_.remove(id_b);
}

TEST_F(ProducerSchedulerTest, AClosedGatePassesTheDeadlinesWithoutProducingAnything) {
    RecordingProducible a("a", 1001, log_);
    test::SwitchedRole role;
    bool& open = role.leading;
    int& asked = role.asked;
    scheduler_.set_role(role);
    // Due every millisecond: the closed gate is asked at several wake-ups.
    const auto id = scheduler_.add(a, due_now(1ms));
    const auto give_up = std::chrono::steady_clock::now() + 10s;
    while (asked < 3 && std::chrono::steady_clock::now() < give_up) {
        clock_.advance(1ms);  // the scheduler reads the fake clock: a deadline falls due
        loop_.restart();
        loop_.run_one_for(1s);
    }
    ASSERT_GE(asked, 3);
    EXPECT_TRUE(log_.empty());
    EXPECT_TRUE(batches_.empty());
    open = true;
    clock_.advance(1ms);
    ASSERT_TRUE(wake());
    EXPECT_EQ(log_, (std::vector<std::string>{"produce a", "send_batch", "sent a"}));
    scheduler_.remove(id);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
