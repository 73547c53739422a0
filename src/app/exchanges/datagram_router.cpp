#include "eip2mqtt/app/exchanges/datagram_router.hpp"

#include <string>
#include <utility>

#include "eip2mqtt/core/wire/decode.hpp"

namespace eip2mqtt::app {

void DatagramRouter::set_consumers(std::span<const std::unique_ptr<ExchangeConsumer>> consumers) {
    by_key_.clear();
    for (const auto& consumer : consumers) by_key_.emplace(consumer->plan().key(), consumer.get());
}

void DatagramRouter::set_followed(std::span<const std::unique_ptr<ExchangeProducer>> producers,
                                  const redundancy::UnitRole& role) {
    produced_.clear();
    role_ = &role;
    if (!role.hears_produced()) return;
    for (const auto& producer : producers) {
        produced_.emplace(producer->plan().key(), producer.get());
    }
}

bool DatagramRouter::heard_produced(const core::wire::Header& header, core::MonoTime now) {
    if (produced_.empty()) return false;
    const auto it = produced_.find(header.key());
    if (it == produced_.end()) return false;
    ++counters_.produced_heard;
    // The other unit's datagram, while the role follows it (UnitRole::follows_produced).
    if (role_->follows_produced(now)) it->second->continue_after(header.request_id);
    return true;
}

void DatagramRouter::route(std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
                           bool truncated, core::MonoTime now) {
    using core::wire::DropReason;
    ++counters_.datagrams;
    if (truncated) {
        count_drop(DropReason::too_long);
        drop_log_.record_lazy(DropReason::too_long, now, [&] {
            return "datagram from " + adapters::udp::to_string(from) + " is larger than 1432 bytes";
        });
        return;
    }
    const auto decoded = core::wire::decode_datagram(bytes);
    if (!decoded) {
        const auto reason = decoded.error();
        count_drop(reason);
        drop_log_.record_lazy(reason, now, [&] {
            return std::to_string(bytes.size()) + " bytes from " + adapters::udp::to_string(from);
        });
        return;
    }
    const auto& datagram = decoded.value();
    const bool produced = heard_produced(datagram.header, now);
    const auto it = by_key_.find(datagram.header.key());
    if (it == by_key_.end()) {
        if (produced) return;
        count_drop(DropReason::unknown_exchange);
        drop_log_.record_lazy(DropReason::unknown_exchange, now, [&] {
            return "producer " + core::wire::to_string(datagram.header.producer_id) + " exchange " +
                   std::to_string(datagram.header.exchange_id) + " from " +
                   adapters::udp::to_string(from) + " is not configured";
        });
        return;
    }
    ExchangeConsumer& consumer = *it->second;
    const auto& spec = consumer.plan().spec;
    if (!consumer.accepts_source(from.address)) {
        count_drop(DropReason::wrong_source);
        drop_log_.record_lazy(DropReason::wrong_source, now, [&] {
            return "exchange " + spec.name + " came from " + adapters::udp::to_string(from) +
                   ", expected " + adapters::udp::ipv4_to_string(spec.source.value_or(0));
        });
        return;
    }
    const auto outcome = consumer.on_datagram(datagram, now, clock_.wall());
    if (outcome.accepted()) {
        ++counters_.accepted;
        return;
    }
    // Its exchange logs a mismatch it enters (ExchangeConsumer, paced when it flaps).
    count_drop(*outcome.dropped);
}

}  // namespace eip2mqtt::app
