#pragma once
/// Logging dropped datagrams without flooding: a core::ThrottledLog per drop reason, so each
/// reason's first drop is logged with its details, then at most one summary per reason per
/// interval; flush() runs on the gateway's tick, so a flood that stops is summarised too.

#include <array>
#include <chrono>
#include <cstdint>
#include <string>

#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"

namespace eip2mqtt::app {

class DropLog {
public:
    explicit DropLog(std::chrono::seconds interval = core::ThrottledLog::default_interval);

    /// Records one drop; logs `detail` (at warn) when this reason has not been logged within
    /// the interval.
    void record(core::wire::DropReason reason, core::MonoTime now, const std::string& detail);
    /// Same, building the detail only when it will be logged.
    template <class DetailFn>
    void record_lazy(core::wire::DropReason reason, core::MonoTime now, DetailFn&& detail) {
        if (const auto count = logs_[static_cast<std::size_t>(reason)].record(now)) {
            emit(reason, count, detail());
        }
    }

    /// Logs, for each reason with drops not logged yet whose last line is at least an interval
    /// old, the summary of those drops. Cheap: one comparison per reason.
    void flush(core::MonoTime now);

private:
    void emit(core::wire::DropReason reason, std::uint64_t count, const std::string& detail);

    std::array<core::ThrottledLog, core::wire::drop_reason_count> logs_;
};

}  // namespace eip2mqtt::app
