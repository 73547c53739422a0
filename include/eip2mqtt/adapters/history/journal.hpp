#pragma once
/// The store-and-forward journal (issue #16): what the exchanges brought while the broker was
/// out of reach, on disk, in arrival order, until the broker acknowledged its replay. SQLite in
/// WAL mode: an entry is written by the commit that follows its append (it then survives the
/// process being killed), and made durable against power loss by the next durable commit, which
/// the caller makes every fsync interval. Bounded: past `max_bytes`, or when the disk is full,
/// the oldest entries are dropped and counted.
///
/// A file SQLite cannot open as a journal of ours is set aside (renamed with `.damaged-{time}`)
/// and a new one is started: the gateway always starts.
///
/// Threading: one thread at a time (it holds one SQLite connection).

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::history {

struct JournalOptions {
    std::string path;  ///< the SQLite file; its directory must exist
    std::uint64_t max_bytes = 256ull << 20;
    /// Tests only, 0 = none: SQLite's max_page_count, past which its writes fail with
    /// SQLITE_FULL exactly as on a full disk (ENOSPC), whatever max_bytes says.
    std::uint64_t disk_full_after_pages = 0;
};

/// One accepted datagram's changes (or a quality change) of one exchange.
struct JournalEntry {
    std::uint64_t id = 0;      ///< given by append(): increasing in arrival order
    std::string exchange;      ///< the exchange's name
    std::uint64_t layout = 0;  ///< the exchange's layout fingerprint when journaled
    std::int64_t timestamp_ms = 0;
    std::uint8_t quality = 0;  ///< core::quality::Quality
    std::string samples;       ///< encode_samples()
};

struct JournalStats {
    std::uint64_t entries = 0;
    std::uint64_t bytes = 0;    ///< of the database and its WAL
    std::uint64_t dropped = 0;  ///< entries dropped for the bound or a full disk, since open
    std::optional<std::int64_t> oldest_timestamp_ms;
};

class Journal {
public:
    /// Opens `options.path`, or creates it. A damaged file is set aside and a new one created;
    /// `set_aside` then says what happened (empty otherwise). Throws std::runtime_error only when
    /// no journal can be created at all (a directory that cannot be written).
    static std::unique_ptr<Journal> open(const JournalOptions& options, std::string& set_aside);
    /// Commits what is open, durably.
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    /// Adds `entry` to the open transaction (begun when needed); sets `entry.id`.
    void append(JournalEntry& entry);
    /// Ends the open transaction, if any: its entries are written (they survive a killed
    /// process); `durable` also syncs them to the disk (they survive a power loss). Then keeps
    /// the bound. A full disk drops the oldest entries until the commit fits.
    void commit(bool durable);
    /// Up to `limit` entries after `after_id`, oldest first.
    std::vector<JournalEntry> oldest(std::size_t limit, std::uint64_t after_id = 0);
    /// Deletes entries (the broker acknowledged their replay).
    void remove(std::span<const std::uint64_t> ids);
    JournalStats stats();

private:
    struct Db;
    explicit Journal(std::unique_ptr<Db> db, JournalOptions options);
    void enforce_bound();
    /// Abandons the open transaction; its entries count as dropped.
    void rollback();
    void drop_oldest(std::uint64_t count);

    std::unique_ptr<Db> db_;
    JournalOptions options_;
    bool in_transaction_ = false;
    std::uint64_t in_transaction_entries_ = 0;
    std::uint64_t dropped_ = 0;
    std::uint64_t table_bound_ = 0;  ///< max_bytes less the WAL's share
};

}  // namespace eip2mqtt::adapters::history
