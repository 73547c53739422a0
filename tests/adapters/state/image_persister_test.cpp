#include "eip2mqtt/adapters/state/image_persister.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::adapters::state {
namespace {

namespace fs = std::filesystem;

std::shared_ptr<const core::plan::ExchangePlan> make_plan(std::string name) {
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
    return std::make_shared<const core::plan::ExchangePlan>(
        core::plan::make_exchange_plan(spec, "acme"));
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
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    /// Attaches a handler that records each completion under `name`.
    ImagePersister::Key attach(ImagePersister& persister, std::string name) {
        return persister.attach([this, name](bool ok, const std::vector<std::uint64_t>& ids) {
            saved_.push_back({name, ok, ids});
        });
    }

    struct Saved {
        std::string name;
        bool ok;
        std::vector<std::uint64_t> write_ids;
    };
    fs::path dir_;
    boost::asio::io_context loop_;
    std::vector<Saved> saved_;
};

TEST_F(ImagePersisterTest, FlushSavesEveryImageAndDeliversTheWriteIdsInOrder) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    const auto b = make_plan("b");
    ImagePersister persister(store, loop_.get_executor());
    const auto key_a = attach(persister, "a");
    const auto key_b = attach(persister, "b");
    persister.save(key_a, a, bytes(1, 2, 3, 4), {10});
    persister.save(key_b, b, bytes(5, 6, 7, 8), {20, 21});
    persister.save(key_a, a, bytes(9, 9, 9, 9), {11});
    persister.flush();

    EXPECT_EQ(store.load(*a), bytes(9, 9, 9, 9));  // the newest image of each exchange
    EXPECT_EQ(store.load(*b), bytes(5, 6, 7, 8));
    std::vector<std::uint64_t> ids_a;
    std::vector<std::uint64_t> ids_b;
    for (const auto& s : saved_) {
        EXPECT_TRUE(s.ok);
        auto& ids = s.name == "a" ? ids_a : ids_b;
        ids.insert(ids.end(), s.write_ids.begin(), s.write_ids.end());
    }
    EXPECT_EQ(ids_a, (std::vector<std::uint64_t>{10, 11}));
    EXPECT_EQ(ids_b, (std::vector<std::uint64_t>{20, 21}));
    // Delivered once: the handler the worker posted finds nothing left.
    const auto delivered = saved_.size();
    loop_.poll();
    EXPECT_EQ(saved_.size(), delivered);
}

TEST_F(ImagePersisterTest, CompletionsReachTheLoopWithoutFlush) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    ImagePersister persister(store, loop_.get_executor());
    const auto key = persister.attach([this](bool ok, const std::vector<std::uint64_t>& ids) {
        saved_.push_back({"a", ok, ids});
        loop_.stop();
    });
    persister.save(key, a, bytes(1, 2, 3, 4), {7});
    // The loop has no work of its own until the worker posts: keep it running until then.
    auto guard = boost::asio::make_work_guard(loop_);
    loop_.run_for(std::chrono::seconds(10));  // returns at the first completion
    ASSERT_EQ(saved_.size(), 1u);
    EXPECT_TRUE(saved_[0].ok);
    EXPECT_EQ(saved_[0].write_ids, std::vector<std::uint64_t>{7});
    EXPECT_EQ(store.load(*a), bytes(1, 2, 3, 4));
}

TEST_F(ImagePersisterTest, FailedSaveIsReportedWithItsWriteIds) {
    fs::create_directories(dir_);
    const auto file = dir_ / "not-a-directory";
    { std::ofstream(file) << "x"; }
    ImageStore store((file / "state").string());
    ImagePersister persister(store, loop_.get_executor());
    persister.save(attach(persister, "a"), make_plan("a"), bytes(1, 2, 3, 4), {5});
    persister.flush();
    ASSERT_EQ(saved_.size(), 1u);
    EXPECT_FALSE(saved_[0].ok);
    EXPECT_EQ(saved_[0].write_ids, std::vector<std::uint64_t>{5});
}

TEST_F(ImagePersisterTest, ADetachedHandlerHearsNothingButItsSaveStillReachesTheDisk) {
    ImageStore store(dir_.string());
    const auto a = make_plan("a");
    const auto b = make_plan("b");
    ImagePersister persister(store, loop_.get_executor());
    const auto key_a = attach(persister, "a");
    const auto key_b = attach(persister, "b");
    EXPECT_NE(key_a, key_b);
    persister.save(key_a, a, bytes(1, 2, 3, 4), {1});
    persister.save(key_b, b, bytes(5, 6, 7, 8), {2});
    persister.detach(key_a);  // exchange a was removed by a reload
    persister.flush();
    ASSERT_EQ(saved_.size(), 1u);
    EXPECT_EQ(saved_[0].name, "b");
    EXPECT_EQ(store.load(*a), bytes(1, 2, 3, 4));
}

}  // namespace
}  // namespace eip2mqtt::adapters::state
