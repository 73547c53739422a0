#pragma once
/// Whether a response answers the request asked (docs/protocol.md §9.2-9.5), for a requester
/// (`discover`): a node that answers one thing for another, by mistake or to mislead, is not
/// taken at its word. Pure.

#include "eip2mqtt/core/command/decode.hpp"

namespace eip2mqtt::core::command {

/// True when `response` carries the request's flag and id, is of its response type or a NAK,
/// and names what the request named: a Retrieve Configuration or Statistics response the same
/// exchange, a Summary page the same index, a Read or Write response the same exchange; a NAK
/// echoes the request's first bytes and names its exchange where the request has one.
bool answers_request(const Request& request, std::span<const std::byte> request_bytes,
                     const Response& response);

}  // namespace eip2mqtt::core::command
