// mqtt_counter: a libmosquitto subscriber that counts publications and measures latency from a
// send time embedded in them. libmosquitto, not Paho: it must never be the bottleneck, and a Paho
// subscriber tops out well below the gateway
// (docs/decisions/0004-bench-subscriber-on-libmosquitto.md).
//
// Per-tag mode (default): counts messages on --filter whose last topic level does not start with
// '_' (skipping _status, _values); the message whose last level is --stamp-tag (default "ts"), or
// every message with --stamp-all, carries CLOCK_REALTIME ns as its value: latency = receive time
// - value. The payload is the gateway's JSON ({"value":V,...}) or a raw value; V is read with
// strtoll after `"value":`, no JSON parser.
// Batch mode (--batch): counts `_values` (and store and forward's `_history`) messages and the
// tag updates they carry (the members of "values"); "ts" inside them is the send time.
// Sparkplug mode (--sparkplug): counts DDATA messages and the metrics they carry (the tag
// updates), decoded with the protobuf classes of the gateway's own .proto; no latency.
// --expect-last V: after the run, how many counted topics ended on value V (newest value wins);
// with --expect-topics N, stops as soon as N topics are on V.
//
// --skip-ms N: latency samples stamped within N ms of the first stamp are left out (counted as
// latency_skipped): the load's first moments, when every process comes out of idle.
// --dump FILE: every latency sample as "ms since the first, latency us", to see where a tail lies.
// --username U --password P: the login, for a broker that wants one (scenario 18's ejabberd).
// Stops after --idle-ms without a counted message (once one arrived), at --expect messages, or
// after --max-s. Prints one JSON line.

#include <mosquitto.h>

#include <atomic>
#include <cstring>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "bench_common.hpp"
#include "mosquitto_session.hpp"
#include "sparkplug_b.pb.h"

namespace {

struct State {
    std::vector<std::string> filters;
    int qos = 0;
    bool batch = false;
    bool sparkplug = false;
    bool stamp_all = false;
    std::string stamp_tag = "ts";
    bool track_last = false;
    long long expected_last = 0;
    std::atomic<std::uint64_t> topics_on_expected{0};  ///< topics whose last value is expected
    std::string ready_file;

    std::atomic<bool> subscribed{false};
    std::atomic<std::uint64_t> messages{0};
    std::atomic<std::int64_t> last_ns{0};
    std::int64_t first_ns = 0;
    std::uint64_t updates = 0;  ///< tag updates (batch mode: members of "values")
    std::uint64_t retained_skipped = 0;
    std::vector<std::int64_t> latency_ns;
    std::vector<std::int64_t> stamps_ns;  ///< with --dump: each latency sample's send time
    bool dump = false;
    std::int64_t skip_ns = 0;   ///< --skip-ms: latency ignored this long after the first stamp
    long long first_stamp = 0;  ///< the first plausible stamp seen
    std::uint64_t latency_skipped = 0;
    std::unordered_map<std::string, long long> last_value;
};

/// The integer after `key` in `payload`, or after nothing when `key` is empty (raw payloads).
bool read_value(const char* payload, int length, const char* key, long long& out) {
    const char* end = payload + length;
    const char* p = payload;
    if (key != nullptr) {
        p = static_cast<const char*>(
            memmem(payload, static_cast<std::size_t>(length), key, std::strlen(key)));
        if (p == nullptr) return false;
        p += std::strlen(key);
    }
    if (p >= end) return false;
    char buffer[32];
    const auto n = std::min<std::size_t>(sizeof buffer - 1, static_cast<std::size_t>(end - p));
    std::memcpy(buffer, p, n);
    buffer[n] = '\0';
    char* parsed = nullptr;
    out = std::strtoll(buffer, &parsed, 10);
    return parsed != buffer;
}

void record_latency(State& s, long long stamp, std::int64_t now_wall) {
    // A plausible CLOCK_REALTIME stamp (after 2001); the overload run's final value is not one.
    if (stamp <= 1000000000000000000LL) return;
    if (s.first_stamp == 0) s.first_stamp = stamp;
    if (stamp - s.first_stamp < s.skip_ns) {
        ++s.latency_skipped;  // the load's start-up, where sender and receiver come out of idle
        return;
    }
    s.latency_ns.push_back(now_wall - stamp);
    if (s.dump) s.stamps_ns.push_back(stamp);
}

void on_connect(mosquitto* mosq, void* user, int rc) {
    auto& s = *static_cast<State*>(user);
    if (rc != 0) {
        std::fprintf(stderr, "mqtt_counter: connect refused (%d)\n", rc);
        return;
    }
    for (const auto& filter : s.filters) {
        mosquitto_subscribe(mosq, nullptr, filter.c_str(), s.qos);
    }
}

void on_subscribe(mosquitto*, void* user, int, int, const int*) {
    auto& s = *static_cast<State*>(user);
    static int acknowledged = 0;
    if (++acknowledged == static_cast<int>(s.filters.size())) {
        bench::touch(s.ready_file);
        s.subscribed = true;
    }
}

void on_message(mosquitto*, void* user, const mosquitto_message* msg) {
    auto& s = *static_cast<State*>(user);
    if (msg->retain) {
        ++s.retained_skipped;
        return;
    }
    const char* slash = std::strrchr(msg->topic, '/');
    const char* level = slash != nullptr ? slash + 1 : msg->topic;
    const auto* payload = static_cast<const char*>(msg->payload);
    const int length = msg->payloadlen;
    const std::int64_t now_wall = bench::wall_ns();
    long long value = 0;
    if (s.sparkplug) {
        // Sparkplug B DDATA: the tag updates are the payload's metrics (decoded with protobuf).
        if (std::strstr(msg->topic, "/DDATA/") == nullptr) return;
        org::eclipse::tahu::protobuf::Payload ddata;
        if (!ddata.ParseFromArray(payload, length)) return;
        s.updates += static_cast<std::uint64_t>(ddata.metrics_size());
    } else if (s.batch) {
        if (std::strcmp(level, "_values") != 0 && std::strcmp(level, "_history") != 0) return;
        const char* values = static_cast<const char*>(
            memmem(payload, static_cast<std::size_t>(length), "\"values\":{", 10));
        if (values == nullptr) return;
        for (const char* p = values + 10; p < payload + length; ++p) s.updates += (*p == ':');
        if (read_value(payload, length, "\"ts\":", value)) record_latency(s, value, now_wall);
    } else {
        if (*level == '_') return;
        ++s.updates;
        const bool stamped = s.stamp_all || s.stamp_tag == level;
        if (stamped || s.track_last) {
            const bool json = length > 0 && payload[0] == '{';
            if (read_value(payload, length, json ? "\"value\":" : nullptr, value)) {
                if (stamped) record_latency(s, value, now_wall);
                if (s.track_last) {
                    auto [it, added] = s.last_value.try_emplace(msg->topic, value);
                    const bool was = !added && it->second == s.expected_last;
                    it->second = value;
                    if (!was && value == s.expected_last) s.topics_on_expected.fetch_add(1);
                    if (was && value != s.expected_last) s.topics_on_expected.fetch_sub(1);
                }
            }
        }
    }
    const std::int64_t now = bench::mono_ns();
    if (s.messages.load(std::memory_order_relaxed) == 0) s.first_ns = now;
    s.last_ns.store(now, std::memory_order_relaxed);
    s.messages.fetch_add(1, std::memory_order_relaxed);
}

/// --dump FILE: one line per latency sample, "ms since the first measured stamp, latency in us",
/// in arrival order: where in the run the tail samples fall (bursts, a period, the start).
void write_dump(const std::string& path, const State& s) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) {
        std::fprintf(stderr, "mqtt_counter: cannot write %s\n", path.c_str());
        return;
    }
    const std::int64_t origin = s.stamps_ns.empty() ? 0 : s.stamps_ns.front();
    for (std::size_t i = 0; i < s.stamps_ns.size(); ++i) {
        std::fprintf(f, "%.3f %.1f\n", static_cast<double>(s.stamps_ns[i] - origin) / 1e6,
                     static_cast<double>(s.latency_ns[i]) / 1e3);
    }
    std::fclose(f);
}

/// Splits `--filter a,b,c`.
std::vector<std::string> split_filters(const std::string& filters) {
    std::vector<std::string> out;
    for (std::size_t start = 0; start <= filters.size();) {
        const auto comma = filters.find(',', start);
        const auto end = comma == std::string::npos ? filters.size() : comma;
        if (end > start) out.push_back(filters.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

/// When to stop counting.
struct Stop {
    std::int64_t idle_ns = 0;         ///< without a counted message, once one arrived
    std::int64_t max_ns = 0;          ///< in all
    std::uint64_t expect = 0;         ///< messages; 0: no such bound
    std::uint64_t expect_topics = 0;  ///< topics on the expected last value; 0: no such bound
};

void read_settings(const bench::Options& opt, State& s, Stop& stop) {
    s.filters = split_filters(opt.str("filter", "#"));
    s.qos = static_cast<int>(opt.num("qos", 0));
    s.batch = opt.has("batch");
    s.sparkplug = opt.has("sparkplug");
    s.stamp_all = opt.has("stamp-all");
    s.stamp_tag = opt.str("stamp-tag", "ts");
    s.track_last = opt.has("expect-last");
    s.expected_last = static_cast<long long>(opt.num("expect-last", 0));
    s.ready_file = opt.str("ready-file", "");
    s.skip_ns = static_cast<std::int64_t>(opt.num("skip-ms", 0) * 1e6);
    s.latency_ns.reserve(8 * 1024 * 1024);
    s.dump = !opt.str("dump", "").empty();
    if (s.dump) s.stamps_ns.reserve(8 * 1024 * 1024);
    stop.expect_topics = static_cast<std::uint64_t>(opt.num("expect-topics", 0));
    stop.idle_ns = static_cast<std::int64_t>(opt.num("idle-ms", 2000) * 1e6);
    stop.max_ns = static_cast<std::int64_t>(opt.num("max-s", 60) * 1e9);
    stop.expect = static_cast<std::uint64_t>(opt.num("expect", 0));
}

/// Waits while libmosquitto's thread counts, until `stop` says.
void count_until(const State& s, const Stop& stop) {
    const std::int64_t start = bench::mono_ns();
    for (;;) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        const std::int64_t now = bench::mono_ns();
        if (now - start > stop.max_ns) break;
        const auto count = s.messages.load(std::memory_order_relaxed);
        if (stop.expect > 0 && count >= stop.expect) break;
        if (stop.expect_topics > 0 && s.topics_on_expected.load() >= stop.expect_topics) break;
        if (count > 0 && now - s.last_ns.load(std::memory_order_relaxed) > stop.idle_ns) break;
    }
}

void print_report(State& s) {
    const auto messages = s.messages.load();
    const double span = static_cast<double>(s.last_ns.load() - s.first_ns) / 1e9;
    std::vector<std::int64_t>& lat = s.latency_ns;
    const double p50 = static_cast<double>(bench::percentile(lat, 0.50)) / 1e3;
    const double p99 = static_cast<double>(bench::percentile(lat, 0.99)) / 1e3;
    const double max = lat.empty() ? 0 : static_cast<double>(lat.back()) / 1e3;
    long long last_ok = 0;
    long long last_bad = 0;
    if (s.track_last) {
        for (const auto& [topic, value] : s.last_value) {
            (value == s.expected_last ? last_ok : last_bad)++;
        }
    }
    std::printf(
        "{\"subscribed\":%s,\"messages\":%llu,\"updates\":%llu,\"first_to_last_s\":%.4f,"
        "\"rate\":%.1f,\"update_rate\":%.1f,\"latency_n\":%zu,\"p50_us\":%.1f,\"p99_us\":%.1f,"
        "\"max_us\":%.1f,\"last_ok\":%lld,\"last_bad\":%lld,\"retained_skipped\":%llu,"
        "\"latency_skipped\":%llu}\n",
        s.subscribed ? "true" : "false", static_cast<unsigned long long>(messages),
        static_cast<unsigned long long>(s.updates), span,
        span > 0 ? static_cast<double>(messages) / span : 0.0,
        span > 0 ? static_cast<double>(s.updates) / span : 0.0, lat.size(), p50, p99, max, last_ok,
        last_bad, static_cast<unsigned long long>(s.retained_skipped),
        static_cast<unsigned long long>(s.latency_skipped));
}

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(
        argc, argv,
        {"host", "port", "filter", "qos", "batch", "sparkplug", "stamp-tag", "stamp-all", "skip-ms",
         "expect-last", "expect-topics", "expect", "idle-ms", "max-s", "ready-file", "id", "dump",
         "username", "password"});
    State s;
    Stop stop;
    read_settings(opt, s, stop);
    mosquitto* mosq = bench::start_mosquitto(opt, "bench-counter", &s,
                                             {on_connect, on_subscribe, on_message}, false);
    count_until(s, stop);
    mosquitto_disconnect(mosq);
    mosquitto_loop_stop(mosq, true);

    if (s.dump) write_dump(opt.str("dump", ""), s);
    print_report(s);
    mosquitto_destroy(mosq);
    mosquitto_lib_cleanup();
    return 0;
}
