#pragma once
/// What the metrics listener answers besides /metrics and the health probes: the status API
/// (docs/operations.md, "Status API"), made by the gateway and asked from the HTTP server's own
/// threads. Read-only: the listener answers GET and HEAD alone there.

#include <functional>
#include <optional>
#include <string>
#include <string_view>

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

}  // namespace eip2mqtt::adapters::metrics
