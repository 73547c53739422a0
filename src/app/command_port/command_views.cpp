#include "eip2mqtt/app/command_port/command_views.hpp"

#include <algorithm>
#include <chrono>

namespace eip2mqtt::app {
namespace {

using core::command::ExchangeMode;
using core::command::ExchangeState;
using core::command::ExchangeView;
using core::command::wrap32;

template <class Duration>
std::uint32_t milliseconds_left(Duration left) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(left).count();
    return static_cast<std::uint32_t>(std::clamp<std::int64_t>(ms, 0, 0xFFFFFFFF));
}

ExchangeView consumed_view(const ExchangeConsumer& consumer, const CommandViewContext& context,
                           core::MonoTime now) {
    const auto& plan = consumer.plan();
    const auto& state = consumer.exchange();
    ExchangeView view;
    view.plan = &plan;
    view.mode = ExchangeMode::consumed;
    view.state = state.state() == core::exchange::ConsumeState::ok ? ExchangeState::active
                                                                   : ExchangeState::idle;
    // Where its data comes from, as the manual's worked example describes a consumed exchange.
    view.destination = plan.spec.source.value_or(plan.spec.producer_id.value);
    view.port = context.data_port;
    view.config_time_s = core::wire_time(consumer.configured_at()).seconds;
    if (const auto deadline = state.next_deadline())
        view.due_time_ms = milliseconds_left(*deadline - now);
    view.messages = wrap32(state.counters().accepted);
    view.missed = wrap32(state.counters().missed);
    view.refresh_errors = wrap32(state.counters().timeouts);
    if (state.has_image()) {
        view.image = state.image();
        view.time_s = state.last_header().time_s;
        view.time_ns = state.last_header().time_ns;
    }
    return view;
}

ExchangeView produced_view(const ExchangeProducer& producer, const CommandViewContext& context,
                           core::WallTime wall) {
    const auto& plan = producer.plan();
    ExchangeView view;
    view.plan = &plan;
    view.mode = ExchangeMode::produced;
    view.state = producer.paused() ? ExchangeState::idle : ExchangeState::active;
    view.destination = producer.destination().address;
    view.destination_type = destination_type(view.destination, context.broadcasts);
    view.port = producer.destination().port;
    view.config_time_s = core::wire_time(producer.configured_at()).seconds;
    const auto& counters = producer.counters();
    view.messages = wrap32(counters.sent);
    view.missed = wrap32(counters.skipped_deadlines);
    view.refresh_errors = wrap32(counters.send_errors);
    view.image = producer.image().data();
    if (const auto sent = producer.last_sent()) {
        const auto sent_at = core::wire_time(*sent);
        view.time_s = sent_at.seconds;
        view.time_ns = sent_at.nanoseconds;
        view.due_time_ms = milliseconds_left(*sent + plan.spec.period - wall);
    }
    view.writable = true;
    return view;
}

}  // namespace

core::command::DestinationType destination_type(std::uint32_t address,
                                                std::span<const std::uint32_t> broadcasts) {
    if ((address >> 28) == 0xE) return core::command::DestinationType::multicast;
    if (address == 0xFFFFFFFF ||
        std::find(broadcasts.begin(), broadcasts.end(), address) != broadcasts.end()) {
        return core::command::DestinationType::broadcast;
    }
    return core::command::DestinationType::unicast;
}

std::vector<ExchangeView> command_views(
    std::span<const std::unique_ptr<ExchangeConsumer>> consumers,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, const CommandViewContext& context,
    core::MonoTime now, core::WallTime wall) {
    std::vector<ExchangeView> views;
    views.reserve(consumers.size() + producers.size());
    for (const auto& consumer : consumers) views.push_back(consumed_view(*consumer, context, now));
    for (const auto& producer : producers) views.push_back(produced_view(*producer, context, wall));
    return views;
}

}  // namespace eip2mqtt::app
