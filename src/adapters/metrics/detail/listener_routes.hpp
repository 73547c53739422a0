#pragma once
/// What the metrics listener answers besides prometheus-cpp's /metrics: /healthz and /readyz,
/// and, while the gateway serves its pages, every other path (the pages say which they serve).
/// With a password set (metrics.auth), every path but /healthz and /readyz asks for it, /metrics
/// too: 401 without it.
/// civetweb's begin_request callback answers them before prometheus-cpp's handlers see the
/// request. The callback is a plain function of the connection, so it finds what the listener
/// a request came to serves by its port.

#include <CivetServer.h>

#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/metrics/health.hpp"
#include "eip2mqtt/adapters/metrics/page_handler.hpp"

namespace eip2mqtt::adapters::metrics::detail {

/// Worker threads of the listener: each serves one connection at a time, so this many slow or
/// silent clients at once are needed before a probe waits.
inline constexpr int server_threads = 24;
/// Event streams open at once, over every listener: each holds a worker for as long as its page
/// is open, and the probes must always find one (a stream beyond is answered 503).
inline constexpr int max_event_streams = 16;
/// How long a connection may take to send its request (and each write to it may take): a
/// client that connects and sends nothing, or half a request line, holds a worker this long,
/// not civetweb's default 30 s. Scrapes and probes send their request at once.
inline constexpr int request_timeout_ms = 2000;

/// civetweb's options for a listener on `listen` (one host:port): server_threads workers,
/// request_timeout_ms, no keep-alive (a connection ends with its answer).
std::vector<std::string> server_options(const std::string& listen);

/// The callbacks to hand prometheus::Exposer; they live as long as the process.
const CivetCallbacks& listener_callbacks();

/// Requests to `port` are answered, until unregister_port(port), from `state`, once they carry
/// `authorization` (the `Authorization` header's value; empty: none asked). Until then, 503.
/// Thread-safe.
void register_port(int port, std::string authorization, std::shared_ptr<const HealthState> state);
/// Requests for the status pages on `port` go to `pages`, event streams to `events` (null:
/// none, 404). Thread-safe.
void register_pages(int port, std::shared_ptr<const PageHandler> pages,
                    std::shared_ptr<const EventSource> events);
/// Nothing more is answered for `port`.
void unregister_port(int port);

}  // namespace eip2mqtt::adapters::metrics::detail
