#include "adapters/metrics/detail/listener_routes.hpp"

#include <civetweb.h>

#include <map>
#include <mutex>
#include <string>
#include <string_view>

#include "adapters/metrics/detail/event_stream.hpp"
#include "eip2mqtt/core/net/basic_auth.hpp"

namespace eip2mqtt::adapters::metrics::detail {
namespace {

struct Routes {
    bool registered = false;    ///< the listener on this port is ours, and set up
    std::string authorization;  ///< the `Authorization` header required; empty: none
    std::shared_ptr<const HealthState> health;
    std::shared_ptr<const PageHandler> pages;
    std::shared_ptr<const EventSource> events;
};

/// Every answer's headers besides its type and length: never cached, and nothing on the page
/// is sniffed, framed or loaded from another origin.
constexpr std::pair<const char*, const char*> common_headers[] = {
    {"Cache-Control", "no-store"},
    {"X-Content-Type-Options", "nosniff"},
    {"X-Frame-Options", "DENY"},
    {"Content-Security-Policy", "default-src 'self'; frame-ancestors 'none'"},
};

std::string header_lines() {
    std::string out;
    for (const auto& [name, value] : common_headers)
        out += std::string(name) + ": " + value + "\r\n";
    return out;
}

struct Registry {
    std::mutex mutex;
    std::map<int, Routes> ports;
};

Registry& registry() {
    static Registry instance;
    return instance;
}

Routes routes_for(int port) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    const auto found = r.ports.find(port);
    return found == r.ports.end() ? Routes{} : found->second;
}

int answer(mg_connection* connection, const HttpAnswer& out, bool head = false) {
    const auto length = std::to_string(out.body.size());
    mg_response_header_start(connection, out.status);
    mg_response_header_add(connection, "Content-Type", out.content_type.c_str(), -1);
    for (const auto& [name, value] : common_headers) {
        mg_response_header_add(connection, name, value, -1);
    }
    if (out.status == 405) mg_response_header_add(connection, "Allow", "GET, HEAD", -1);
    if (out.status == 401) {
        mg_response_header_add(connection, "WWW-Authenticate",
                               R"(Basic realm="eip2mqtt", charset="UTF-8")", -1);
    }
    mg_response_header_add(connection, "Content-Length", length.c_str(), -1);
    mg_response_header_send(connection);
    if (!head) mg_write(connection, out.body.data(), out.body.size());
    // civetweb takes a positive return as "answered", with this status for its access log.
    return out.status;
}

int answer_health(mg_connection* connection, std::string_view path, const HealthState& state) {
    const auto now = state.clock().monotonic();
    const auto said = path == "/healthz" ? state.liveness(now) : state.readiness(now);
    return answer(connection, {said.status, "text/plain; charset=utf-8", said.body});
}

HttpAnswer api_error(int status, std::string_view text) {
    return {status, "application/json", R"({"error":")" + std::string(text) + "\"}"};
}

/// The status page and its API: read-only, GET and HEAD alone.
int answer_api(mg_connection* connection, const mg_request_info& request, std::string_view path,
               const Routes& routes) {
    const std::string_view method = request.request_method ? request.request_method : "";
    if (method != "GET" && method != "HEAD") {
        return answer(connection, api_error(405, "read-only: GET or HEAD"));
    }
    if (path == "/api/events" && method == "GET" && routes.events) {
        const int port = request.server_port;
        static const std::string headers = header_lines();
        return stream_events(connection, request.query_string, headers,
                             [port] { return routes_for(port).events; });
    }
    const auto* pages = routes.pages.get();
    std::optional<HttpAnswer> out;
    if (pages != nullptr) out = (*pages)(path);
    return answer(connection, out ? *out : api_error(404, "no such page"), method == "HEAD");
}

int begin_request(mg_connection* connection) {
    const auto* request = mg_get_request_info(connection);
    if (request == nullptr || request->local_uri == nullptr) return 0;
    const std::string_view path = request->local_uri;
    const auto routes = routes_for(request->server_port);
    // Between civetweb's start and the endpoint's registration: not knowing whether the
    // listener asks for a password, it answers nothing yet.
    if (!routes.registered) return answer(connection, {503, "text/plain", "starting\n"});
    if ((path == "/healthz" || path == "/readyz") && routes.health) {
        return answer_health(connection, path, *routes.health);
    }
    if (!routes.authorization.empty()) {
        const char* given = mg_get_header(connection, "Authorization");
        if (given == nullptr || !core::net::same_secret(given, routes.authorization)) {
            return answer(connection, {401, "text/plain", "authentication required\n"});
        }
    }
    // Every other path but prometheus-cpp's is the pages': they say which they serve.
    if (routes.pages && path != "/metrics") return answer_api(connection, *request, path, routes);
    return 0;
}

CivetCallbacks make_callbacks() {
    CivetCallbacks callbacks;
    callbacks.begin_request = begin_request;
    return callbacks;
}

}  // namespace

std::vector<std::string> server_options(const std::string& listen) {
    return {"listening_ports",    listen,
            "num_threads",        std::to_string(server_threads),
            "request_timeout_ms", std::to_string(request_timeout_ms),
            "enable_keep_alive",  "no"};
}

const CivetCallbacks& listener_callbacks() {
    static const CivetCallbacks callbacks = make_callbacks();
    return callbacks;
}

void register_port(int port, std::string authorization, std::shared_ptr<const HealthState> state) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    auto& routes = r.ports[port];
    routes.registered = true;
    routes.authorization = std::move(authorization);
    routes.health = std::move(state);
}

void register_pages(int port, std::shared_ptr<const PageHandler> pages,
                    std::shared_ptr<const EventSource> events) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    r.ports[port].pages = std::move(pages);
    r.ports[port].events = std::move(events);
}

void unregister_port(int port) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    r.ports.erase(port);
}

}  // namespace eip2mqtt::adapters::metrics::detail
