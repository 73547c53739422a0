// The journal's writer thread: batches handed over are appended in order, one after
// the other, flush() waits for them, with() sees only whole batches, and the destructor leaves
// everything committed on disk.

#include "eip2mqtt/adapters/history/journal_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::history {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

class JournalWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ =
            fs::temp_directory_path() / ("eip2mqtt_journal_writer_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::unique_ptr<Journal> open() {
        std::string set_aside;
        return Journal::open({(dir_ / "history.sqlite").string(), 256ull << 20}, set_aside);
    }
    static std::vector<JournalEntry> batch(std::int64_t first, int count) {
        std::vector<JournalEntry> entries;
        for (int i = 0; i < count; ++i) entries.push_back({0, "plant", 7, first + i, 1, "x"});
        return entries;
    }

    fs::path dir_;
};

TEST_F(JournalWriterTest, BatchesAreAppendedInOrderAndSurviveTheWriter) {
    {
        JournalWriter writer(open());
        for (int b = 0; b < 50; ++b) {
            auto entries = batch(b * 10, 10);
            writer.append(entries, b % 10 == 0);
            EXPECT_TRUE(entries.empty());
        }
        writer.flush();
        EXPECT_TRUE(writer.idle());
        EXPECT_EQ(writer.with([](Journal& j) { return j.stats().entries; }), 500u);
        auto more = batch(500, 5);
        writer.append(more, false);
    }  // the destructor appends and commits the last batch
    auto journal = open();
    const auto entries = journal->oldest(1000);
    ASSERT_EQ(entries.size(), 505u);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        EXPECT_EQ(entries[i].timestamp_ms, static_cast<std::int64_t>(i));
        if (i > 0) {
            EXPECT_GT(entries[i].id, entries[i - 1].id);
        }
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::history
