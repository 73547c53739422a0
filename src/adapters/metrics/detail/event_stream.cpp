#include "adapters/metrics/detail/event_stream.hpp"

#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>

#include "adapters/metrics/detail/listener_routes.hpp"

namespace eip2mqtt::adapters::metrics::detail {
namespace {

using namespace std::chrono_literals;

/// Holds one of the max_event_streams places while a stream is open.
class StreamPlace {
public:
    StreamPlace() : taken_(open().fetch_add(1) < max_event_streams) {
        if (!taken_) open().fetch_sub(1);
    }
    ~StreamPlace() {
        if (taken_) open().fetch_sub(1);
    }
    StreamPlace(const StreamPlace&) = delete;
    StreamPlace& operator=(const StreamPlace&) = delete;
    bool taken() const { return taken_; }

private:
    static std::atomic<int>& open() {
        static std::atomic<int> count{0};
        return count;
    }
    bool taken_;
};

bool write_all(mg_connection* connection, const std::string& text) {
    return mg_write(connection, text.data(), text.size()) == static_cast<int>(text.size());
}

}  // namespace

std::vector<std::string> open_names(const char* query) {
    std::vector<std::string> names;
    if (query == nullptr) return names;
    std::string value(std::strlen(query) + 1, '\0');
    const int length = mg_get_var(query, std::strlen(query), "open", value.data(), value.size());
    if (length <= 0) return names;
    value.resize(static_cast<std::size_t>(length));
    for (std::size_t at = 0; at <= value.size();) {
        const auto comma = std::min(value.find(',', at), value.size());
        if (comma > at) names.push_back(value.substr(at, comma - at));
        at = comma + 1;
    }
    return names;
}

int stream_events(mg_connection* connection, const char* query, const std::string& headers,
                  const std::function<std::shared_ptr<const EventSource>()>& current) {
    const StreamPlace place;
    if (!place.taken()) {
        const std::string busy =
            "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\n"
            "Content-Length: 22\r\nConnection: close\r\n" +
            headers + "\r\ntoo many event streams";
        write_all(connection, busy);
        return 503;
    }
    const auto names = open_names(query);
    if (!write_all(connection,
                   "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\n"
                   "Connection: close\r\n" +
                       headers + "\r\n")) {
        return 200;
    }
    // The client's going shows as a failed write; the gateway's stopping as no source.
    for (auto source = current(); source; source = current()) {
        const auto events = (*source)(names);
        if (!events || !write_all(connection, *events)) break;
        std::this_thread::sleep_for(1s);
    }
    return 200;
}

}  // namespace eip2mqtt::adapters::metrics::detail
