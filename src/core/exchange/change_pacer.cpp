#include "eip2mqtt/core/exchange/change_pacer.hpp"

#include <algorithm>

namespace eip2mqtt::core::exchange {

void ChangePacer::report(MonoTime now) {
    paced_ = std::max(paced_, now) + period_;
    holding_ = false;
}

bool ChangePacer::on_change(MonoTime now) {
    if (period_.count() > 0 && now < earliest()) {
        holding_ = true;
        return false;
    }
    report(now);
    return true;
}

bool ChangePacer::take_due(MonoTime now) {
    if (!holding_ || now < earliest()) return false;
    report(now);
    return true;
}

std::optional<MonoTime> ChangePacer::next_due() const {
    if (!holding_) return std::nullopt;
    return earliest();
}

}  // namespace eip2mqtt::core::exchange
