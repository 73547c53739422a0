// The journal on a really full disk, a 2 MB tmpfs: the kernel's ENOSPC, not a simulated limit.
// Filled, then full to the last byte by another file, it keeps taking the newest entries and
// dropping the oldest, deletes what the replay acknowledged, and opens again after a restart
// with every entry it had. And a journal path that is a symbolic link is never followed.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/history/journal.hpp"
#include "tests/support/tmpfs.hpp"

namespace eip2mqtt::adapters::history {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using test::Tmpfs;

constexpr std::uint64_t tmpfs_bytes = 2 << 20;
constexpr std::uint64_t unbounded = 256ull << 20;  // the default max_mb: the disk is the bound

JournalEntry entry(std::int64_t timestamp) {
    return {0,         "plant", 42,
            timestamp, 1,       std::string(600, static_cast<char>('a' + timestamp % 26))};
}

/// Writes entries stamped `first`, `first + 1`... in batches of `batch`, as the writer thread
/// does; returns the next stamp.
std::int64_t write_entries(Journal& journal, std::int64_t first, int count, int batch = 50) {
    for (int done = 0; done < count; done += batch) {
        std::vector<JournalEntry> entries;
        for (int i = 0; i < batch; ++i) entries.push_back(entry(first + done + i));
        journal.write(entries, done % 500 == 0);
    }
    return first + count;
}

/// The journal holds the newest entries up to `last`, in order, none missing between them,
/// and says so in its figures.
void expect_newest_through(Journal& journal, std::int64_t last) {
    const auto left = journal.oldest(1000000);
    ASSERT_FALSE(left.empty());
    EXPECT_EQ(journal.stats().entries, left.size());
    EXPECT_EQ(left.back().timestamp_ms, last);
    for (std::size_t i = 1; i < left.size(); ++i) {
        ASSERT_EQ(left[i].timestamp_ms, left[i - 1].timestamp_ms + 1) << "at " << i;
        ASSERT_GT(left[i].id, left[i - 1].id);
    }
    EXPECT_EQ(left.back().samples, entry(last).samples);
}

class JournalFullDiskTest : public ::testing::Test {
protected:
    void SetUp() override {
        disk_ = std::make_unique<Tmpfs>(tmpfs_bytes);
        if (!disk_->mounted()) GTEST_SKIP() << disk_->error();
    }
    std::unique_ptr<Journal> open(std::string* set_aside = nullptr) {
        std::string aside;
        auto journal = Journal::open({path(), unbounded}, aside);
        if (set_aside) *set_aside = aside;
        EXPECT_TRUE(set_aside || aside.empty()) << aside;
        return journal;
    }
    std::string path() const { return disk_->path() + "/history.sqlite"; }

    std::unique_ptr<Tmpfs> disk_;
};

TEST_F(JournalFullDiskTest, AFullDiskKeepsTheNewestAcrossDeletionsAndARestart) {
    auto journal = open();
    // Far more than 2 MB: the disk, not max_bytes, bounds the journal.
    auto next = write_entries(*journal, 0, 6000);
    auto stats = journal->stats();
    EXPECT_GT(stats.dropped, 0u);
    EXPECT_GT(stats.entries, 1000u) << "the disk's room is used";
    EXPECT_LE(stats.bytes, tmpfs_bytes);
    expect_newest_through(*journal, next - 1);

    // Something else takes the rest of the disk: every write now meets ENOSPC.
    disk_->fill("other-file");
    ASSERT_LT(disk_->free_bytes(), 4096u);
    next = write_entries(*journal, next, 3000);
    EXPECT_GT(journal->stats().entries, 100u);
    expect_newest_through(*journal, next - 1);

    // The replay's deletions go through on the full disk, and the journal goes on after them.
    auto oldest = journal->oldest(200);
    std::vector<std::uint64_t> ids;
    for (const auto& e : oldest) ids.push_back(e.id);
    const auto before = journal->stats().entries;
    journal->remove(ids);
    EXPECT_EQ(journal->stats().entries, before - ids.size());
    journal->remove_through(journal->oldest(100).back().id);
    EXPECT_EQ(journal->stats().entries, before - ids.size() - 100);
    next = write_entries(*journal, next, 1000);
    expect_newest_through(*journal, next - 1);
    const auto kept = journal->stats().entries;

    // A restart on the still full disk (what the closed WAL gave back taken as well): the same
    // journal, not set aside, taking entries.
    journal.reset();
    disk_->fill("other-file-2");
    ASSERT_LT(disk_->free_bytes(), 4096u);
    std::string set_aside;
    journal = open(&set_aside);
    EXPECT_EQ(set_aside, "");
    EXPECT_EQ(journal->stats().entries, kept);
    expect_newest_through(*journal, next - 1);
    next = write_entries(*journal, next, 2000);
    expect_newest_through(*journal, next - 1);
    stats = journal->stats();
    EXPECT_GT(stats.entries, 100u);
}

TEST_F(JournalFullDiskTest, ADiskFullBeforeTheJournalOpensStillTakesEntries) {
    {
        auto journal = open();
        write_entries(*journal, 0, 100);
    }
    disk_->fill("other-file");
    auto journal = open();
    EXPECT_EQ(journal->stats().entries, 100u);
    const auto next = write_entries(*journal, 100, 500);
    expect_newest_through(*journal, next - 1);
}

class JournalSymlinkTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() / ("eip2mqtt_journal_" + std::string(info->name()) + "_" +
                                             std::to_string(::getpid()));
        fs::remove_all(root_);
        fs::create_directories(root_ / "state");
        fs::create_directories(root_ / "elsewhere");
    }
    void TearDown() override { fs::remove_all(root_); }

    fs::path root_;
};

TEST_F(JournalSymlinkTest, AJournalPathThatIsASymbolicLinkIsNeverFollowed) {
    // An empty file outside the state directory: SQLite would take it for a new database.
    const auto target = root_ / "elsewhere" / "precious";
    std::ofstream(target).close();
    const auto path = root_ / "state" / "history.sqlite";
    fs::create_symlink(target, path);
    std::string set_aside;
    auto journal = Journal::open({path.string(), 1 << 20}, set_aside);
    EXPECT_NE(set_aside.find("symbolic link"), std::string::npos) << set_aside;
    std::vector<JournalEntry> entries{entry(1)};
    journal->write(entries, true);
    EXPECT_EQ(fs::file_size(target), 0u) << "the link was followed";
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(path)));
    EXPECT_EQ(journal->oldest(10).size(), 1u);
}

TEST_F(JournalSymlinkTest, ASymbolicLinkBesideTheJournalIsNeverWrittenThrough) {
    const auto path = root_ / "state" / "history.sqlite";
    for (const auto* suffix : {"-wal", "-reserve"}) {
        const auto target = root_ / "elsewhere" / (std::string("target") + suffix);
        std::ofstream(target).close();
        fs::create_symlink(target, path.string() + suffix);
    }
    std::string set_aside;
    auto journal = Journal::open({path.string(), 1 << 20}, set_aside);
    std::vector<JournalEntry> entries{entry(1), entry(2)};
    journal->write(entries, true);
    for (const auto* suffix : {"-wal", "-reserve"}) {
        EXPECT_EQ(fs::file_size(root_ / "elsewhere" / (std::string("target") + suffix)), 0u)
            << suffix << " was followed";
    }
    EXPECT_EQ(journal->oldest(10).size(), 2u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::history
