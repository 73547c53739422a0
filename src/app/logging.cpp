#include "eip2mqtt/app/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdlib>

namespace eip2mqtt::app {

void setup_logging(const std::string& level) {
    auto logger = spdlog::stderr_color_mt("eip2mqtt");
    if (std::getenv("JOURNAL_STREAM") != nullptr) {
        // journald stamps each line itself; a second timestamp is noise.
        logger->set_pattern("%l: %v");
    } else {
        logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%l%$: %v");
    }
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
