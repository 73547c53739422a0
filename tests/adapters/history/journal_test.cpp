// The store-and-forward journal (issue #16) on a real SQLite file: entries come back oldest
// first and resume after an id, survive a reopen, are deleted once acknowledged, the bound drops
// the oldest and counts them, and a damaged or foreign file is set aside.

#include "eip2mqtt/adapters/history/journal.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::history {
namespace {

namespace fs = std::filesystem;

class JournalTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("eip2mqtt_journal_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::unique_ptr<Journal> open(std::uint64_t max_bytes = 256ull << 20) {
        std::string set_aside;
        auto journal = Journal::open({path(), max_bytes}, set_aside);
        set_aside_ = set_aside;
        return journal;
    }
    std::string path() const { return (dir_ / "history.db").string(); }

    static JournalEntry entry(std::int64_t timestamp, std::size_t bytes = 8) {
        return {0, "plant", 42, timestamp, 1, std::string(bytes, 'x')};
    }

    /// Appends `count` entries of 400 bytes (entry i stamped i), committing every 100, into a
    /// journal with room for fewer: some are dropped, the rest counted, the newest kept.
    static std::pair<JournalStats, std::vector<JournalEntry>> fill_past_its_room(Journal& journal,
                                                                                 int count) {
        for (int i = 0; i < count; ++i) {
            auto e = entry(i, 400);
            journal.append(e);
            if (i % 100 == 99) journal.commit(false);
        }
        journal.commit(false);
        const auto stats = journal.stats();
        EXPECT_GT(stats.dropped, 0u);
        EXPECT_EQ(stats.entries + stats.dropped, static_cast<std::uint64_t>(count));
        auto left = journal.oldest(100000);
        EXPECT_EQ(left.size(), stats.entries);
        EXPECT_FALSE(left.empty());
        if (!left.empty()) {
            EXPECT_EQ(left.back().timestamp_ms, count - 1);
        }
        return {stats, std::move(left)};
    }

    fs::path dir_;
    std::string set_aside_;
};

TEST_F(JournalTest, EntriesComeBackOldestFirstAndResumeAfterAnId) {
    auto journal = open();
    EXPECT_TRUE(set_aside_.empty());
    std::vector<std::uint64_t> ids;
    for (int i = 0; i < 5; ++i) {
        auto e = entry(1000 + i);
        journal->append(e);
        ids.push_back(e.id);
    }
    journal->commit(false);
    EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
    const auto first = journal->oldest(2);
    ASSERT_EQ(first.size(), 2u);
    EXPECT_EQ(first[0].timestamp_ms, 1000);
    EXPECT_EQ(first[0].exchange, "plant");
    EXPECT_EQ(first[0].layout, 42u);
    EXPECT_EQ(first[0].quality, 1);
    EXPECT_EQ(first[0].samples, std::string(8, 'x'));
    const auto rest = journal->oldest(10, first[1].id);
    ASSERT_EQ(rest.size(), 3u);
    EXPECT_EQ(rest[0].timestamp_ms, 1002);
    const auto stats = journal->stats();
    EXPECT_EQ(stats.entries, 5u);
    EXPECT_EQ(stats.oldest_timestamp_ms, 1000);
    EXPECT_GT(stats.bytes, 0u);
}

TEST_F(JournalTest, CommittedEntriesSurviveAReopenAndAcknowledgedOnesAreGone) {
    std::vector<std::uint64_t> ids;
    {
        auto journal = open();
        for (int i = 0; i < 4; ++i) {
            auto e = entry(i);
            journal->append(e);
            ids.push_back(e.id);
        }
        journal->commit(true);
        const std::vector<std::uint64_t> acknowledged{ids[0], ids[1]};
        journal->remove(acknowledged);
    }
    auto journal = open();
    const auto left = journal->oldest(10);
    ASSERT_EQ(left.size(), 2u);
    EXPECT_EQ(left[0].id, ids[2]);
    EXPECT_EQ(journal->stats().entries, 2u);
    // Ids never come back, even after the newest were deleted.
    const std::vector<std::uint64_t> all{ids[2], ids[3]};
    journal->remove(all);
    auto e = entry(9);
    journal->append(e);
    EXPECT_GT(e.id, ids[3]);
}

TEST_F(JournalTest, TheBoundDropsTheOldestAndCountsThem) {
    auto journal = open(256 << 10);  // 256 KiB
    const auto [stats, left] = fill_past_its_room(*journal, 2000);
    ASSERT_FALSE(left.empty());
    EXPECT_EQ(left.front().timestamp_ms, static_cast<std::int64_t>(stats.dropped));
}

TEST_F(JournalTest, AFullDiskDropsTheOldestAndCountsThem) {
    // The disk fills up far below max_bytes: SQLite's writes fail with SQLITE_FULL, as they do
    // on ENOSPC (here from its page limit: 64 pages of 4 KiB).
    std::string set_aside;
    auto journal = Journal::open({path(), 256ull << 20, 64}, set_aside);
    const auto [stats, left] = fill_past_its_room(*journal, 4000);
    // The newest survive, in order (entry i carries i as its sample time: no clock is read),
    // and the journal takes entries again.
    for (std::size_t i = 1; i < left.size(); ++i) {
        EXPECT_LT(left[i - 1].timestamp_ms, left[i].timestamp_ms);
    }
    auto e = entry(4000);
    journal->append(e);
    journal->commit(false);
    EXPECT_EQ(journal->oldest(100000).back().timestamp_ms, 4000);
}

TEST_F(JournalTest, ADamagedFileIsSetAsideAndANewJournalStarts) {
    std::ofstream(path(), std::ios::binary) << std::string(8192, '\x5a');
    auto journal = open();
    EXPECT_NE(set_aside_.find("cannot be read"), std::string::npos) << set_aside_;
    EXPECT_EQ(journal->stats().entries, 0u);
    bool kept = false;
    for (const auto& file : fs::directory_iterator(dir_)) {
        kept = kept || file.path().filename().string().starts_with("history.db.damaged-");
    }
    EXPECT_TRUE(kept);
    auto e = entry(1);
    journal->append(e);
    journal->commit(true);
    EXPECT_EQ(journal->oldest(10).size(), 1u);
}

TEST_F(JournalTest, AnotherApplicationsDatabaseIsNeverTakenForAJournal) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path().c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, "CREATE TABLE accounts(id INTEGER, balance REAL)", nullptr, nullptr,
                           nullptr),
              SQLITE_OK);
    sqlite3_close(db);
    auto journal = open();
    EXPECT_NE(set_aside_.find("not an eip2mqtt journal"), std::string::npos) << set_aside_;
    EXPECT_EQ(journal->stats().entries, 0u);
}

}  // namespace
}  // namespace eip2mqtt::adapters::history
