#pragma once
/// Logging on the data path without flooding: each reason's first occurrence is logged with its
/// details, then at most one summary per reason per interval with the count since the last line
/// (style.md "Errors": count every error, log the first, then one summary per interval).
/// The summary comes with the next drop of its reason, or from flush() (called on the gateway's
/// tick) once the interval has passed, so a flood that stops is summarised all the same.

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"

namespace eip2mqtt::app {

class DropLog {
public:
    explicit DropLog(std::chrono::seconds interval = std::chrono::seconds(60))
        : interval_(interval) {}

    /// Records one drop; logs `detail` (at warn) when this reason has not been logged within
    /// the interval.
    void record(core::wire::DropReason reason, core::MonoTime now, const std::string& detail);
    /// Same, building the detail only when it will be logged.
    template <class DetailFn>
    void record_lazy(core::wire::DropReason reason, core::MonoTime now, DetailFn&& detail) {
        auto& entry = entries_[static_cast<std::size_t>(reason)];
        ++entry.pending;
        if (!entry.logged_at || now - *entry.logged_at >= interval_) {
            emit(reason, now, detail());
        }
    }

    /// Logs, for each reason with drops not logged yet whose last line is at least an interval
    /// old, the summary of those drops. Cheap: one comparison per reason.
    void flush(core::MonoTime now);

private:
    struct Entry {
        std::optional<core::MonoTime> logged_at;
        std::uint64_t pending = 0;  ///< drops since the last line
    };
    void emit(core::wire::DropReason reason, core::MonoTime now, const std::string& detail);

    std::chrono::seconds interval_;
    std::array<Entry, core::wire::drop_reason_count> entries_{};
};

}  // namespace eip2mqtt::app
