#include "eip2mqtt/app/logging.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <memory>

namespace eip2mqtt::app {
namespace {

/// The last warnings and errors, for the status page: the sink lives as long as the process.
std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt>& warnings_sink() {
    static auto sink = [] {
        auto made = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(kept_warnings);
        made->set_level(spdlog::level::warn);
        // The time of day in UTC, as the page shows every other time: the line is read apart.
        made->set_formatter(std::make_unique<spdlog::pattern_formatter>(
            "%Y-%m-%dT%H:%M:%S.%eZ %l: %v", spdlog::pattern_time_type::utc));
        return made;
    }();
    return sink;
}

}  // namespace

std::vector<std::string> recent_warnings() {
    auto lines = warnings_sink()->last_formatted();
    for (auto& line : lines) {
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    }
    return lines;
}

void setup_logging(const std::string& level) {
    auto logger = spdlog::stderr_color_mt("eip2mqtt");
    if (std::getenv("JOURNAL_STREAM") != nullptr) {
        // journald stamps each line itself; a second timestamp is noise.
        logger->set_pattern("%l: %v");
    } else {
        logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%l%$: %v");
    }
    // After the pattern, which the logger would give every sink: the kept lines have their own.
    logger->sinks().push_back(warnings_sink());
    spdlog::set_default_logger(logger);
    set_log_level(level);
}

void set_log_level(const std::string& level) {
    const auto parsed = spdlog::level::from_str(level);
    // from_str answers `off` for names it does not know.
    if (parsed == spdlog::level::off && level != "off") {
        spdlog::warn("unknown log level '{}', using info", level);
        spdlog::set_level(spdlog::level::info);
        return;
    }
    spdlog::set_level(parsed);
}

}  // namespace eip2mqtt::app
