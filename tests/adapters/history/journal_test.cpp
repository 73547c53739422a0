// The store-and-forward journal on a real SQLite file: entries come back oldest
// first and resume after an id, survive a reopen, are deleted once acknowledged, the bound drops
// the oldest and counts them, and a damaged or foreign file is set aside. A full disk (a real
// tmpfs) and a symbolic link are in journal_full_disk_test.cpp.

#include "eip2mqtt/adapters/history/journal.hpp"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::history {
namespace EIP2MQTT_THIS_FILE {

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
    static void write_one(Journal& journal, JournalEntry e) {
        std::vector<JournalEntry> one{std::move(e)};
        journal.write(one, false);
    }

    /// What the journal's files take on disk, as the filesystem sees them.
    std::uint64_t bytes_on_disk() const {
        std::uint64_t total = 0;
        for (const auto& file : fs::directory_iterator(dir_)) {
            if (file.is_regular_file()) total += file.file_size();
        }
        return total;
    }

    fs::path dir_;
    std::string set_aside_;
};

TEST_F(JournalTest, EntriesComeBackOldestFirstAndResumeAfterAnId) {
    auto journal = open();
    EXPECT_TRUE(set_aside_.empty());
    std::vector<JournalEntry> entries;
    for (int i = 0; i < 5; ++i) entries.push_back(entry(1000 + i));
    journal->write(entries, false);
    for (std::size_t i = 1; i < entries.size(); ++i) {
        EXPECT_GT(entries[i].id, entries[i - 1].id);
    }
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

TEST_F(JournalTest, WrittenEntriesSurviveAReopenAndAcknowledgedOnesAreGone) {
    std::vector<JournalEntry> entries;
    {
        auto journal = open();
        for (int i = 0; i < 4; ++i) entries.push_back(entry(i));
        journal->write(entries, true);
        const std::vector<std::uint64_t> acknowledged{entries[0].id, entries[1].id};
        journal->remove(acknowledged);
    }
    auto journal = open();
    const auto left = journal->oldest(10);
    ASSERT_EQ(left.size(), 2u);
    EXPECT_EQ(left[0].id, entries[2].id);
    EXPECT_EQ(journal->stats().entries, 2u);
    // Ids never come back, even after the newest were deleted.
    journal->remove_through(entries[3].id);
    EXPECT_EQ(journal->stats().entries, 0u);
    auto e = entry(9);
    std::vector<JournalEntry> one{e};
    journal->write(one, false);
    EXPECT_GT(one[0].id, entries[3].id);
}

TEST_F(JournalTest, RemoveThroughDeletesEveryEntryUpToAnId) {
    auto journal = open();
    std::vector<JournalEntry> entries;
    for (int i = 0; i < 10; ++i) entries.push_back(entry(i));
    journal->write(entries, false);
    journal->remove_through(entries[6].id);
    const auto left = journal->oldest(100);
    ASSERT_EQ(left.size(), 3u);
    EXPECT_EQ(left[0].timestamp_ms, 7);
    EXPECT_EQ(journal->stats().entries, 3u);
}

TEST_F(JournalTest, TheBoundDropsTheOldestAndCountsThem) {
    auto journal = open(256 << 10);  // 256 KiB
    constexpr int count = 2000;
    for (int i = 0; i < count; i += 100) {
        std::vector<JournalEntry> batch;
        for (int j = i; j < i + 100; ++j) batch.push_back(entry(j, 400));
        journal->write(batch, false);
        EXPECT_LE(bytes_on_disk(), 256u << 10) << "after entry " << i + 99;
    }
    const auto stats = journal->stats();
    EXPECT_GT(stats.dropped, 0u);
    EXPECT_EQ(stats.entries + stats.dropped, static_cast<std::uint64_t>(count));
    const auto left = journal->oldest(100000);
    ASSERT_EQ(left.size(), stats.entries);
    ASSERT_FALSE(left.empty());
    // The newest are kept, in order, and none is missing between them.
    EXPECT_EQ(left.front().timestamp_ms, static_cast<std::int64_t>(stats.dropped));
    EXPECT_EQ(left.back().timestamp_ms, count - 1);
}

TEST_F(JournalTest, TheBoundHoldsForABatchManyTimesItsSize) {
    // A slow moment piles up a tick's worth far beyond the bound: written at once, it must not
    // take the WAL, nor the file, past max_bytes on the way.
    constexpr std::uint64_t max_bytes = 1 << 20;
    auto journal = open(max_bytes);
    std::vector<JournalEntry> batch;
    for (int i = 0; i < 2000; ++i) batch.push_back(entry(i, 1400));  // 2.8 MB
    journal->write(batch, false);
    EXPECT_LE(bytes_on_disk(), max_bytes);
    const auto stats = journal->stats();
    EXPECT_LE(stats.bytes, max_bytes);
    EXPECT_EQ(stats.bytes, bytes_on_disk());
    EXPECT_GT(stats.entries, 300u);  // the bound is used, not left empty
    EXPECT_EQ(stats.entries + stats.dropped, 2000u);
    const auto left = journal->oldest(100000);
    ASSERT_FALSE(left.empty());
    EXPECT_EQ(left.back().timestamp_ms, 1999);
    EXPECT_EQ(left.front().timestamp_ms, static_cast<std::int64_t>(stats.dropped));
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
    write_one(*journal, entry(1));
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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::history
