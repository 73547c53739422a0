#pragma once
/// What the metrics listener answers besides /metrics and the health probes: the status API
/// and its page (docs/operations.md, "Status API"), made by the gateway and asked from the HTTP
/// server's own threads. Read-only: the listener answers GET and HEAD alone there.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::adapters::metrics {

struct HttpAnswer {
    int status = 200;
    std::string content_type = "application/json";
    std::string body;
};

/// The answer to a GET of `path` (the request's path, percent-decoded, without its query), or
/// nullopt for a path it does not serve (404). Called on the server's threads, several at once;
/// it may wait a short while for the gateway's loop.
using PageHandler = std::function<std::optional<HttpAnswer>(std::string_view path)>;

/// The next events of a stream (GET /api/events, text/event-stream), asked about once a second
/// with the exchanges the page has open (its `open` parameter: names, comma-separated): one or
/// more `event: NAME\ndata: ...\n\n`, or nullopt to end the stream. Called like PageHandler.
using EventSource = std::function<std::optional<std::string>(const std::vector<std::string>& open)>;

}  // namespace eip2mqtt::adapters::metrics
