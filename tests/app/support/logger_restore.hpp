#pragma once
// For the tests of the commands that set up logging themselves (setup_logging registers the
// logger `eip2mqtt` and makes it the default, at a level of their own): fresh() lets the next
// one register it again, and the destructor puts back the default logger and the level of
// before, so that the tests after them in the same process log as before.

#include <spdlog/spdlog.h>

#include <memory>

namespace eip2mqtt::test {

class LoggerRestore {
public:
    LoggerRestore() = default;
    ~LoggerRestore() {
        spdlog::drop("eip2mqtt");
        spdlog::set_default_logger(previous_);
        spdlog::set_level(level_);
    }
    LoggerRestore(const LoggerRestore&) = delete;
    LoggerRestore& operator=(const LoggerRestore&) = delete;

    /// Before each command that calls setup_logging.
    static void fresh() { spdlog::drop("eip2mqtt"); }

private:
    std::shared_ptr<spdlog::logger> previous_ = spdlog::default_logger();
    spdlog::level::level_enum level_ = spdlog::get_level();
};

}  // namespace eip2mqtt::test
