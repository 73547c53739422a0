#include "eip2mqtt/adapters/state/image_persister.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::adapters::state {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

core::plan::ExchangePlan make_plan(std::string name) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.direction = core::plan::Direction::produce;
    spec.exchange_id = 10;
    spec.destination = "127.0.0.1";
    spec.topic = name;
    core::plan::TagSpec value;
    value.name = "VALUE";
    value.address = {0, 0};
    value.type = core::plan::TagType::dint;
    value.writable = true;
    spec.tags = {value};
    return core::plan::make_exchange_plan(spec, "acme");
}

std::vector<std::byte> bytes(unsigned char a, unsigned char b, unsigned char c, unsigned char d) {
    return {std::byte{a}, std::byte{b}, std::byte{c}, std::byte{d}};
}

class ImagePersisterTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_persister_" + std::string(info->name()) +
                                            "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    /// Attaches a handler that records each completion under `name`.
    ImagePersister::Key attach(ImagePersister& persister, std::string name) {
        return persister.attach([this, name](const std::optional<std::string>& error) {
            saved_.push_back({name, error});
        });
    }

    struct Saved {
        std::string name;
        std::optional<std::string> error;
    };
    fs::path dir_;
    boost::asio::io_context loop_;
    std::vector<Saved> saved_;
};

TEST_F(ImagePersisterTest, FlushSavesEveryImageInOrderAndDeliversEachCompletionOnce) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    const auto b = make_plan("b");
    ImagePersister persister(store, loop_.get_executor());
    const auto key_a = attach(persister, "a");
    const auto key_b = attach(persister, "b");
    const auto file_a = persister.open(a);
    persister.save(key_a, file_a, bytes(1, 2, 3, 4));
    persister.save(key_b, persister.open(b), bytes(5, 6, 7, 8));
    persister.save(key_a, file_a, bytes(9, 9, 9, 9));
    persister.flush();

    EXPECT_EQ(store.load(a), bytes(9, 9, 9, 9));  // the newest image of each exchange
    EXPECT_EQ(store.load(b), bytes(5, 6, 7, 8));
    ASSERT_EQ(saved_.size(), 3u);
    EXPECT_EQ(saved_[0].name, "a");
    EXPECT_EQ(saved_[1].name, "b");
    EXPECT_EQ(saved_[2].name, "a");
    for (const auto& s : saved_) EXPECT_EQ(s.error, std::nullopt);
    // Delivered once: the handler the worker posted finds nothing left.
    loop_.poll();
    EXPECT_EQ(saved_.size(), 3u);
}

TEST_F(ImagePersisterTest, FlushAlsoWaitsForTheSavesItsHandlersQueue) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    ImagePersister persister(store, loop_.get_executor());
    const auto file = persister.open(a);
    int completions = 0;
    ImagePersister::Key key = 0;
    key = persister.attach([&](const std::optional<std::string>&) {
        // An exchange saves again what it was asked while its first save was under way.
        if (++completions == 1) persister.save(key, file, bytes(2, 2, 2, 2));
    });
    persister.save(key, file, bytes(1, 1, 1, 1));
    persister.flush();
    EXPECT_EQ(completions, 2);
    EXPECT_EQ(store.load(a), bytes(2, 2, 2, 2));
}

TEST_F(ImagePersisterTest, CompletionsReachTheLoopWithoutFlush) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    ImagePersister persister(store, loop_.get_executor());
    const auto key = persister.attach([this](const std::optional<std::string>& error) {
        saved_.push_back({"a", error});
        loop_.stop();
    });
    persister.save(key, persister.open(a), bytes(1, 2, 3, 4));
    // The loop has no work of its own until the worker posts: keep it running until then.
    auto guard = boost::asio::make_work_guard(loop_);
    loop_.run_for(std::chrono::seconds(10));  // returns at the first completion
    ASSERT_EQ(saved_.size(), 1u);
    EXPECT_EQ(saved_[0].error, std::nullopt);
    EXPECT_EQ(store.load(a), bytes(1, 2, 3, 4));
}

TEST_F(ImagePersisterTest, AFailedSaveIsReportedWithWhatFailed) {
    const auto file = dir_ / "not-a-directory";
    { std::ofstream(file) << "x"; }
    ImageStore store((file / "state").string());
    ImagePersister persister(store, loop_.get_executor());
    const auto plan = make_plan("a");
    persister.save(attach(persister, "a"), persister.open(plan), bytes(1, 2, 3, 4));
    persister.flush();
    ASSERT_EQ(saved_.size(), 1u);
    ASSERT_TRUE(saved_[0].error.has_value());
    EXPECT_EQ(*saved_[0].error,
              "open " + (file / "state" / "a.image.tmp").string() + ": Not a directory");
}

TEST_F(ImagePersisterTest, ADetachedOrUnattendedSaveIsHeardByNobodyButStillReachesTheDisk) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    const auto b = make_plan("b");
    const auto c = make_plan("c");
    ImagePersister persister(store, loop_.get_executor());
    const auto key_a = attach(persister, "a");
    const auto key_b = attach(persister, "b");
    EXPECT_NE(key_a, key_b);
    EXPECT_NE(key_a, ImagePersister::unattended);
    persister.save(key_a, persister.open(a), bytes(1, 2, 3, 4));
    persister.save(key_b, persister.open(b), bytes(5, 6, 7, 8));
    persister.save(ImagePersister::unattended, persister.open(c), bytes(9, 9, 9, 9));
    persister.detach(key_a);  // exchange a was removed by a reload
    persister.flush();
    ASSERT_EQ(saved_.size(), 1u);
    EXPECT_EQ(saved_[0].name, "b");
    EXPECT_EQ(store.load(a), bytes(1, 2, 3, 4));
    EXPECT_EQ(store.load(c), bytes(9, 9, 9, 9));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::state
