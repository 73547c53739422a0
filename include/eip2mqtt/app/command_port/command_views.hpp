#pragma once
/// The gateway's running exchanges as the command responder sees them (core::command::
/// ExchangeView): configuration, state, counters and image, consumers first, then producers,
/// whose plans are the handles their writes are staged by (ExchangeWrite::producer).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"
#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "eip2mqtt/core/command/exchange_view.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

struct CommandViewContext {
    std::uint16_t data_port = 18246;        ///< eip.port, where consumed data comes
    std::vector<std::uint32_t> broadcasts;  ///< the host's broadcast addresses
};

/// How a produced exchange's destination is described: multicast (224.0.0.0/4), broadcast
/// (255.255.255.255 or a broadcast address of this host), else unicast.
core::command::DestinationType destination_type(std::uint32_t address,
                                                std::span<const std::uint32_t> broadcasts);

std::vector<core::command::ExchangeView> command_views(
    std::span<const std::unique_ptr<ExchangeConsumer>> consumers,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, const CommandViewContext& context,
    core::MonoTime now, core::WallTime wall);

}  // namespace eip2mqtt::app
