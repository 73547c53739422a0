#include "eip2mqtt/app/drop_log.hpp"

#include <spdlog/spdlog.h>

namespace eip2mqtt::app {

void DropLog::record(core::wire::DropReason reason, core::MonoTime now, const std::string& detail) {
    record_lazy(reason, now, [&] { return detail; });
}

void DropLog::flush(core::MonoTime now) {
    for (const auto reason : core::wire::all_drop_reasons) {
        auto& entry = entries_[static_cast<std::size_t>(reason)];
        if (entry.pending == 0 || !entry.logged_at || now - *entry.logged_at < interval_) continue;
        // The detail of each drop is built only when it is logged, so none is at hand here.
        spdlog::warn("dropped {} datagram{} ({}) in the last {} s", entry.pending,
                     entry.pending == 1 ? "" : "s", core::wire::to_string(reason),
                     interval_.count());
        entry.pending = 0;
        entry.logged_at = now;
    }
}

void DropLog::emit(core::wire::DropReason reason, core::MonoTime now, const std::string& detail) {
    auto& entry = entries_[static_cast<std::size_t>(reason)];
    if (entry.pending <= 1) {
        spdlog::warn("dropped datagram ({}): {}", core::wire::to_string(reason), detail);
    } else {
        spdlog::warn("dropped {} datagrams ({}) in the last {} s; latest: {}", entry.pending,
                     core::wire::to_string(reason), interval_.count(), detail);
    }
    entry.pending = 0;
    entry.logged_at = now;
}

}  // namespace eip2mqtt::app
