#pragma once
/// The last writes this unit received and what became of each, for the status page
/// (docs/operations.md, "Status page and API"): when, by which protocol, to what, the values,
/// and the result once given (`ok`, `ok, not saved: …`, a refusal's reason), or `pending`. A
/// write's reply carries its entry's id (WriteReply::log_id), by which its result finds it.
///
/// Threading: the loop only.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

struct WriteRequest;

class WriteLog {
public:
    /// Entries kept: beyond, the oldest goes.
    static constexpr std::size_t kept = 100;

    /// A write received at `at`; the id its result is given by (never 0).
    std::uint64_t arrived(const WriteRequest& request, core::WallTime at);
    /// The result of write `id` (`ok`, or why not) at `at`, replacing any earlier one (a write
    /// handed to another unit, then settled); nothing when it is no longer kept.
    void answered(std::uint64_t id, std::string_view result, core::WallTime at);

    /// `[{"id":3,"time":…,"origin":"mqtt","target":"…","values":"SP=5","result":"ok",
    /// "answered_at":…},…]`, newest first; `result` null while pending.
    void append_json(std::string& out) const;
    std::size_t size() const { return entries_.size(); }

private:
    struct Entry {
        std::uint64_t id = 0;
        std::int64_t at_ms = 0;
        std::string_view origin;
        std::string target;
        std::string values;
        std::optional<std::string> result;
        std::int64_t answered_ms = 0;
    };

    std::deque<Entry> entries_;
    std::uint64_t next_id_ = 1;
};

}  // namespace eip2mqtt::app
