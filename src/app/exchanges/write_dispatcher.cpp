// Writes (docs/mqtt-api.md "Writes"): a northbound decodes a write whole (the JSON tree's
// WriteRouter checks a message on a `…/set` topic); what it accepts is staged on its produced
// exchange, whose result is reported once the datagram carrying it has left, and what it or the
// exchange refuses is answered at once with a reason. Nothing is changed by a rejected write,
// and one bad value rejects a multi-tag write.

#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::app {

WriteDispatcher::WriteDispatcher(StageWrite stage, Northbound& results, const core::Clock& clock)
    : stage_(std::move(stage)), results_(results), clock_(clock) {}

bool WriteDispatcher::admitted(WriteRequest& request) {
    using redundancy::WriteTurn;
    switch (role_->admit_write(request, counters_)) {
        case WriteTurn::apply:
            return true;
        case WriteTurn::taken:
            write_log_.answered(request.reply.log_id, "handed to the other unit", clock_.wall());
            return false;
        case WriteTurn::refused:
            break;
    }
    reject(request, role_->refusal());
    return false;
}

bool WriteDispatcher::settle(WriteRequest&& request) {
    if (role_->settle_write(request, counters_) == redundancy::WriteTurn::refused) {
        reject(request, role_->refusal());
        return false;
    }
    const bool write = std::holds_alternative<ExchangeWrite>(request.outcome);
    on_write(std::move(request));
    return write;
}

void WriteDispatcher::on_write(WriteRequest&& request) {
    // A write settled on taking the lead was logged as it arrived, and left.
    if (request.reply.log_id == 0) {
        request.reply.log_id = write_log_.arrived(request, clock_.wall());
    }
    if (!admitted(request)) return;
    if (const auto* rejection = std::get_if<core::write::WriteRejection>(&request.outcome)) {
        return reject(request, *rejection);
    }
    if (auto rejection = stage_(std::get<ExchangeWrite>(std::move(request.outcome)), request.reply,
                                clock_.monotonic())) {
        return reject(request, *rejection);
    }
    ++counters_.writes_ok;
    ++counters_.writes_by_origin[static_cast<std::size_t>(request.reply.via)];
}

void WriteDispatcher::reject(const WriteRequest& request,
                             const core::write::WriteRejection& rejection) {
    ++counters_.writes_rejected[static_cast<std::size_t>(rejection.error)];
    results_.write_result(request.reply, rejection.message);
    const auto count = log_.record(clock_.monotonic());
    if (count == 0) return;
    std::uint64_t total = 0;
    for (const auto n : counters_.writes_rejected) total += n;
    const auto summary = count == 1 ? fmt::format("{} rejected so far", total)
                                    : fmt::format("{} rejected in the last {} s, {} so far", count,
                                                  log_.interval().count(), total);
    spdlog::warn("write to {} rejected: {}{}{} ({})", core::printable(request.target),
                 core::printable(rejection.message), request.log_detail,
                 request.reply.topic.empty() ? " (no valid topic to answer on)" : "", summary);
}

}  // namespace eip2mqtt::app
