// Process-wide logging: the line format with and without journald, and the level names.

#include "eip2mqtt/app/logging.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

/// Runs each test on a fresh "eip2mqtt" logger and gives the earlier default one back after.
class LoggingTest : public testing::Test {
protected:
    void SetUp() override {
        spdlog::drop("eip2mqtt");
        const char* journal = std::getenv("JOURNAL_STREAM");
        if (journal != nullptr) journal_ = journal;
        level_ = spdlog::get_level();
    }
    void TearDown() override {
        if (journal_.empty()) {
            unsetenv("JOURNAL_STREAM");
        } else {
            setenv("JOURNAL_STREAM", journal_.c_str(), 1);
        }
        spdlog::drop("eip2mqtt");
        spdlog::set_default_logger(previous_);
        spdlog::set_level(level_);
    }
    /// What one info line `text` writes to stderr after setup_logging(level).
    static std::string line_of(const std::string& level, const std::string& text) {
        testing::internal::CaptureStderr();
        setup_logging(level);
        spdlog::info("{}", text);
        spdlog::default_logger()->flush();
        return testing::internal::GetCapturedStderr();
    }

private:
    std::shared_ptr<spdlog::logger> previous_ = spdlog::default_logger();
    spdlog::level::level_enum level_ = spdlog::level::info;
    std::string journal_;
};

TEST_F(LoggingTest, UnderJournaldALineHasNoTimestamp) {
    setenv("JOURNAL_STREAM", "8:1234", 1);
    EXPECT_EQ(line_of("info", "hello"), "info: hello\n");
}

TEST_F(LoggingTest, ElsewhereALineStartsWithItsTime) {
    unsetenv("JOURNAL_STREAM");
    EXPECT_THAT(line_of("info", "hello"),
                testing::MatchesRegex("[0-9]{4}-[0-9]{2}-[0-9]{2} [0-9]{2}:[0-9]{2}:[0-9]{2}"
                                      "\\.[0-9]{3} info: hello\n"));
}

TEST_F(LoggingTest, TheLevelFiltersLines) {
    setenv("JOURNAL_STREAM", "8:1234", 1);
    EXPECT_EQ(line_of("warn", "hidden"), "");
    EXPECT_EQ(spdlog::get_level(), spdlog::level::warn);
}

TEST_F(LoggingTest, AnUnknownLevelIsInfoWithAWarning) {
    setenv("JOURNAL_STREAM", "8:1234", 1);
    EXPECT_EQ(line_of("loud", "shown"),
              "warning: unknown log level 'loud', using info\ninfo: shown\n");
    EXPECT_EQ(spdlog::get_level(), spdlog::level::info);
}

TEST_F(LoggingTest, KnownLevelsAreSetOffIncluded) {
    set_log_level("debug");
    EXPECT_EQ(spdlog::get_level(), spdlog::level::debug);
    set_log_level("off");
    EXPECT_EQ(spdlog::get_level(), spdlog::level::off);
}

TEST_F(LoggingTest, TheLastWarningsAndErrorsAreKeptForTheStatusPage) {
    testing::internal::CaptureStderr();
    setup_logging("info");
    spdlog::info("not kept");
    for (int i = 1; i <= 60; ++i) spdlog::warn("warning {}", i);
    spdlog::error("an error");
    (void)testing::internal::GetCapturedStderr();
    const auto kept = recent_warnings();
    ASSERT_EQ(kept.size(), kept_warnings);
    EXPECT_THAT(kept.front(), testing::EndsWith("Z warning: warning 12"));
    EXPECT_THAT(kept[kept.size() - 2], testing::EndsWith("Z warning: warning 60"));
    EXPECT_THAT(
        kept.back(),
        testing::MatchesRegex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:]{8}\\.[0-9]{3}Z error: an error"));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
