#include "adapters/metrics/detail/health_pages.hpp"

#include <civetweb.h>

#include <map>
#include <mutex>
#include <string>
#include <string_view>

namespace eip2mqtt::adapters::metrics::detail {
namespace {

struct Registry {
    std::mutex mutex;
    std::map<int, std::shared_ptr<const HealthState>> states;
};

Registry& registry() {
    static Registry instance;
    return instance;
}

std::shared_ptr<const HealthState> state_for(int port) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    const auto found = r.states.find(port);
    return found == r.states.end() ? nullptr : found->second;
}

int answer(mg_connection* connection, const HealthAnswer& health) {
    const auto length = std::to_string(health.body.size());
    mg_response_header_start(connection, health.status);
    mg_response_header_add(connection, "Content-Type", "text/plain; charset=utf-8", -1);
    mg_response_header_add(connection, "Cache-Control", "no-store", -1);
    mg_response_header_add(connection, "Content-Length", length.c_str(), -1);
    mg_response_header_send(connection);
    mg_write(connection, health.body.data(), health.body.size());
    // civetweb takes a positive return as "answered", with this status for its access log.
    return health.status;
}

int begin_request(mg_connection* connection) {
    const auto* request = mg_get_request_info(connection);
    if (request == nullptr || request->local_uri == nullptr) return 0;
    const std::string_view path = request->local_uri;
    if (path != "/healthz" && path != "/readyz") return 0;
    const auto state = state_for(request->server_port);
    if (!state) return 0;
    const auto now = state->clock().monotonic();
    return answer(connection, path == "/healthz" ? state->liveness(now) : state->readiness(now));
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

const CivetCallbacks& health_callbacks() {
    static const CivetCallbacks callbacks = make_callbacks();
    return callbacks;
}

void register_health(int port, std::shared_ptr<const HealthState> state) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    r.states[port] = std::move(state);
}

void unregister_health(int port) {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    r.states.erase(port);
}

}  // namespace eip2mqtt::adapters::metrics::detail
