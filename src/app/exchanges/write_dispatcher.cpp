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

WriteDispatcher::WriteDispatcher(StageWrite stage, const core::Clock& clock)
    : stage_(std::move(stage)), clock_(clock) {}

bool WriteDispatcher::admitted(WriteRequest& request) {
    using core::redundancy::WritePolicy;
    const auto policy = admission_.policy ? admission_.policy() : WritePolicy::apply;
    if (policy == WritePolicy::apply) return true;
    if (policy == WritePolicy::leave_to_leader && request.reply.via != WriteOrigin::commands) {
        ++counters_.writes_left_to_leader;
        if (admission_.leave) admission_.leave(std::move(request));
        return false;
    }
    reject(request, {core::write::WriteError::standby, "standby"});
    return false;
}

bool WriteDispatcher::settle(WriteRequest&& request) {
    const auto* write = std::get_if<ExchangeWrite>(&request.outcome);
    if (write && !(admission_.holds && admission_.holds(*write))) {
        ++counters_.writes_settled_standby;
        reject(request, {core::write::WriteError::standby, "standby"});
        return false;
    }
    if (write) ++counters_.writes_settled_applied;
    on_write(std::move(request));
    return write != nullptr;
}

void WriteDispatcher::on_write(WriteRequest&& request) {
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
    if (request.reply.origin) request.reply.origin->write_result(request.reply, rejection.message);
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
