#include "adapters/mqtt/detail/sender_log.hpp"

#include <spdlog/spdlog.h>

#include <cstdint>

#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

void SenderLog::refused(const std::string& topic, const std::string& problem) {
    std::uint64_t count = 0;
    {
        std::lock_guard lock(mutex_);
        count = refused_log_.record(clock_.monotonic());
    }
    if (count > 0) {
        spdlog::error(
            "{} publication to {} dropped: a broker would refuse it ({}) and close the "
            "connection ({} dropped since last report)",
            log_name_, core::printable(topic), problem, count);
    }
}

void SenderLog::publish_failure(const std::string& topic, const std::string& reason) {
    std::uint64_t count = 0;
    {
        std::lock_guard lock(mutex_);
        count = publish_failure_log_.record(clock_.monotonic());
    }
    if (count > 0) {
        spdlog::warn("{} publish to {} failed: {} ({} failures since last report)", log_name_,
                     topic, reason, count);
    }
}

void SenderLog::dropped_suspect(const std::string& topic) {
    spdlog::error(
        "{} publication to {} failed again when it was sent alone (the broker closed the "
        "connection on it, or Paho refused it): it is dropped, so that it cannot block every "
        "connection after",
        log_name_, core::printable(topic));
}

}  // namespace eip2mqtt::adapters::mqtt::detail
