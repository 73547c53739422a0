#include "eip2mqtt/app/exchanges/drop_log.hpp"

#include <spdlog/spdlog.h>

namespace eip2mqtt::app {

DropLog::DropLog(std::chrono::seconds interval) { logs_.fill(core::ThrottledLog(interval)); }

void DropLog::record(core::wire::DropReason reason, core::MonoTime now, const std::string& detail) {
    record_lazy(reason, now, [&] { return detail; });
}

void DropLog::flush(core::MonoTime now) {
    for (const auto reason : core::wire::all_drop_reasons) {
        auto& log = logs_[static_cast<std::size_t>(reason)];
        if (const auto count = log.flush(now)) {
            // The detail of each drop is built only when it is logged, so none is at hand here.
            spdlog::warn("dropped {} datagram{} ({}) in the last {} s", count,
                         count == 1 ? "" : "s", core::wire::to_string(reason),
                         log.interval().count());
        }
    }
}

void DropLog::emit(core::wire::DropReason reason, std::uint64_t count, const std::string& detail) {
    if (count == 1) {
        spdlog::warn("dropped datagram ({}): {}", core::wire::to_string(reason), detail);
    } else {
        spdlog::warn("dropped {} datagrams ({}) in the last {} s; latest: {}", count,
                     core::wire::to_string(reason),
                     logs_[static_cast<std::size_t>(reason)].interval().count(), detail);
    }
}

}  // namespace eip2mqtt::app
