#pragma once
/// GET /api/events: Server-Sent Events (text/event-stream) to the status page, one batch of
/// events about once a second, on the civetweb worker that took the request, for as long as
/// the page stays open and the gateway serves its pages.

#include <civetweb.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/metrics/page_handler.hpp"

namespace eip2mqtt::adapters::metrics::detail {

/// The `open` parameter of a query string (`open=a,b%20c`): the names, decoded; none when
/// absent.
std::vector<std::string> open_names(const char* query);

/// Streams to `connection` what the source `current()` returns (read again before each batch:
/// null, or a source that says nullopt, ends the stream), until the client goes. `headers` are
/// the security headers every answer carries. Returns the status for civetweb's log.
int stream_events(mg_connection* connection, const char* query, const std::string& headers,
                  const std::function<std::shared_ptr<const EventSource>()>& current);

}  // namespace eip2mqtt::adapters::metrics::detail
