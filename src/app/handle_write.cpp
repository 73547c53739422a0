// MQTT writes (docs/mqtt-api.md "Writes"; issue #3): the WriteRouter checks a message on a `…/set`
// topic whole; what it accepts is staged on its produced exchange, whose result is published
// once the datagram carrying it has left, and what it refuses is answered at once with a
// reason. Nothing is changed by a rejected write, and one bad value rejects a multi-tag write.

#include <spdlog/spdlog.h>

#include "eip2mqtt/adapters/mqtt/payload.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::app {

void Gateway::build_write_routes() {
    write_router_.clear();
    write_router_.set_options(
        {config_.mqtt.base_topic, config_.mqtt.allow_response_topics_under_base});
    for (const auto& consumer : consumers_) write_router_.add(consumer->plan(), std::nullopt);
    for (std::size_t i = 0; i < producers_.size(); ++i) write_router_.add(producers_[i]->plan(), i);
}

std::vector<std::string> Gateway::write_subscriptions() const {
    return write_router_.subscriptions();
}

void Gateway::reject_write(const WriteReply& reply, const std::string& target,
                           const core::write::WriteRejection& rejection,
                           const std::string& detail) {
    ++counters_.writes_rejected[static_cast<std::size_t>(rejection.error)];
    if (!reply.topic.empty()) {
        mqtt_->publish({reply.topic, adapters::mqtt::format_write_result(rejection.message), 1,
                        false, false, reply.correlation_data});
    }
    // Each is answered and counted; the log is throttled (a client may flood).
    if (const auto count = rejected_write_log_.record(std::chrono::steady_clock::now())) {
        std::uint64_t total = 0;
        for (const auto n : counters_.writes_rejected) total += n;
        const auto summary = count == 1
                                 ? fmt::format("{} rejected so far", total)
                                 : fmt::format("{} rejected in the last {} s, {} so far", count,
                                               rejected_write_log_.interval().count(), total);
        spdlog::warn("write to {} rejected: {}{}{} ({})", core::printable(target),
                     core::printable(rejection.message), detail,
                     reply.topic.empty() ? " (no valid topic to answer on)" : "", summary);
    }
}

void Gateway::on_message(adapters::mqtt::Incoming message) {
    auto decision = write_router_.route(message);
    if (!decision) return;
    if (const auto* rejection = std::get_if<core::write::WriteRejection>(&decision->outcome)) {
        const auto detail = decision->response_topic_problem.empty()
                                ? std::string()
                                : " (the response topic " +
                                      core::printable(message.response_topic) + " " +
                                      decision->response_topic_problem + "; answered on " +
                                      decision->reply.topic + ")";
        return reject_write(decision->reply, message.topic, *rejection, detail);
    }
    auto& routed = std::get<RoutedWrite>(decision->outcome);
    if (auto rejection = producers_[routed.producer]->stage(
            std::move(routed.writes), decision->reply, std::chrono::steady_clock::now())) {
        return reject_write(decision->reply, message.topic, *rejection);
    }
    ++counters_.writes_ok;
}

}  // namespace eip2mqtt::app
