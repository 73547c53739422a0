#pragma once
/// Helpers shared by the bench programs: `--key value` options, clocks and percentiles.
/// Bench-only; nothing here is part of the gateway.

#include <sys/socket.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <string>
#include <vector>

namespace bench {

/// `--key value` and `--flag` options; unknown keys are an error so that a typo in run.py
/// never silently measures the wrong thing.
class Options {
public:
    Options(int argc, char** argv, std::vector<std::string> known) : known_(std::move(known)) {
        for (int i = 1; i < argc; ++i) {
            std::string key = argv[i];
            if (key.rfind("--", 0) != 0) fail("unexpected argument " + key);
            key = key.substr(2);
            if (std::find(known_.begin(), known_.end(), key) == known_.end()) {
                fail("unknown option --" + key);
            }
            if (i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0) {
                values_[key] = argv[++i];
            } else {
                values_[key] = "";
            }
        }
    }
    bool has(const std::string& key) const { return values_.count(key) != 0; }
    std::string str(const std::string& key, const std::string& fallback) const {
        const auto it = values_.find(key);
        return it == values_.end() ? fallback : it->second;
    }
    double num(const std::string& key, double fallback) const {
        const auto it = values_.find(key);
        return it == values_.end() ? fallback : std::strtod(it->second.c_str(), nullptr);
    }
    [[noreturn]] static void fail(const std::string& message) {
        std::fprintf(stderr, "error: %s\n", message.c_str());
        std::exit(2);
    }

private:
    std::vector<std::string> known_;
    std::map<std::string, std::string> values_;
};

inline std::int64_t now_ns(clockid_t clock) {
    timespec ts{};
    clock_gettime(clock, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}
inline std::int64_t mono_ns() { return now_ns(CLOCK_MONOTONIC); }
inline std::int64_t wall_ns() { return now_ns(CLOCK_REALTIME); }

/// The kernel's receive time (CLOCK_REALTIME ns) of a datagram received with SO_TIMESTAMPNS on,
/// from its control messages; `fallback` when it carries none.
inline std::int64_t kernel_receive_ns(msghdr& header, std::int64_t fallback) {
    for (cmsghdr* c = CMSG_FIRSTHDR(&header); c != nullptr; c = CMSG_NXTHDR(&header, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
            timespec ts{};
            std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
            return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
        }
    }
    return fallback;
}

inline void sleep_until_mono(std::int64_t deadline_ns) {
    timespec ts{static_cast<time_t>(deadline_ns / 1000000000),
                static_cast<long>(deadline_ns % 1000000000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
    }
}

/// The q-quantile (0..1) of `values` (sorted in place); 0 when empty.
template <class T>
T percentile(std::vector<T>& values, double q) {
    if (values.empty()) return T{};
    std::sort(values.begin(), values.end());
    const auto index = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
    return values[std::min(index, values.size() - 1)];
}

/// Creates `path` (empty) to tell the driver this program is ready.
inline void touch(const std::string& path) {
    if (path.empty()) return;
    if (FILE* f = std::fopen(path.c_str(), "w")) std::fclose(f);
}

}  // namespace bench
