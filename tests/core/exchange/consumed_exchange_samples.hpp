#pragma once
/// The exchange and datagrams the tests of ConsumedExchange feed it
/// (tests/core/exchange/consumed_exchange*_test.cpp). For the tests only: it adds its names to
/// the namespace.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::exchange {

using namespace std::chrono_literals;
using test::from_hex;
using test::to_hex;
using wire::DropReason;
using wire::Signature;
namespace vectors = test::vectors;

inline MonoTime at(std::chrono::milliseconds offset) { return MonoTime{} + offset; }

inline plan::ExchangePlan make_plan(std::uint16_t length = 15,
                                    std::chrono::milliseconds timeout = 3000ms,
                                    Signature signature = {}) {
    plan::ExchangePlan plan;
    plan.spec.name = "test";
    plan.spec.producer_id = wire::ProducerId{0xC0A80101};
    plan.spec.exchange_id = 1;
    plan.spec.signature = signature;
    plan.length = length;
    plan.timeout = timeout;
    return plan;
}

/// A datagram of the exchange with owned data.
struct Sample {
    wire::Header header;
    std::vector<std::byte> data;

    wire::Datagram datagram() const { return {header, data}; }
};

inline Sample sample(std::uint16_t request_id, std::size_t size = 15, Signature signature = {},
                     std::byte fill = std::byte{0x11}) {
    Sample s;
    s.header.request_id = request_id;
    s.header.producer_id = wire::ProducerId{0xC0A80101};
    s.header.exchange_id = 1;
    s.header.signature = signature.to_wire();
    s.data.assign(size, fill);
    return s;
}

/// Datagram with V5's header (signature 2.5) and `size` data bytes: V5 itself has none.
inline Sample v5_with_data(std::size_t size = 15) {
    Sample s;
    s.header = wire::decode_header(from_hex(vectors::v5));
    s.data.assign(size, std::byte{0x42});
    return s;
}

inline ConsumeOutcome feed(ConsumedExchange& exchange, const Sample& s,
                           std::chrono::milliseconds when = 0ms) {
    return exchange.on_datagram(s.datagram(), at(when));
}

}  // namespace eip2mqtt::core::exchange
