#include "eip2mqtt/core/exchange/change_log.hpp"

#include <algorithm>

namespace eip2mqtt::core::exchange {

bool ChangeLog::summarising(MonoTime now) const {
    // Flapping goes on while changes keep coming within an interval of the last one counted.
    if (summarised_at_ && now - *summarised_at_ < interval()) return true;
    // The oldest of the last `burst` lines within the interval: that many changes already.
    const auto& oldest = singles_.front();
    return oldest && now - *oldest < interval();
}

ChangeLog::Line ChangeLog::on_change(MonoTime now) {
    if (!summarising(now)) {
        std::shift_left(singles_.begin(), singles_.end(), 1);
        singles_.back() = now;
        return {true, 0};
    }
    summarised_at_ = now;
    return {false, summary_.record(now)};
}

}  // namespace eip2mqtt::core::exchange
