#pragma once
/// The store-and-forward journal: what the exchanges brought while the broker was
/// out of reach, on disk, in arrival order, until the broker acknowledged its replay. SQLite in
/// WAL mode: an entry is written by the commit that ends its write() (it then survives the
/// process being killed), and made durable against power loss by the next durable write,
/// which the caller makes every fsync interval.
///
/// Bounded at all times: the database, its WAL and its reserve (a file of allocated blocks the
/// journal gives up to make room on a full disk) together never take more than `max_bytes`,
/// nor more than the filesystem has room for. Past that, and whenever the disk is full, the
/// oldest entries are dropped and counted, and the newest kept; the journal never stops taking
/// entries for lack of room, at open either.
///
/// A file SQLite cannot open as a journal of ours (damaged, another application's database, a
/// directory, a symbolic link: never followed) is set aside (renamed with `.damaged-{time}`)
/// and a new one is started: the gateway always starts.
///
/// Threading: one thread at a time (it holds one SQLite connection, in exclusive locking mode:
/// no other process opens the journal while it is open).

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::adapters::history {

namespace detail {
class Reserve;
struct SpacePlan;
}  // namespace detail

struct JournalOptions {
    std::string path;  ///< the SQLite file; its directory must exist
    std::uint64_t max_bytes = 256ull << 20;
    /// Stamps the name of a damaged file set aside; outlives the open.
    const core::Clock* clock = &adapters::clock::system_clock();
};

/// One accepted datagram's changes (or a quality change) of one exchange.
struct JournalEntry {
    std::uint64_t id = 0;      ///< given by write(): increasing in arrival order
    std::string exchange;      ///< the exchange's name
    std::uint64_t layout = 0;  ///< the exchange's layout fingerprint when journaled
    std::int64_t timestamp_ms = 0;
    std::uint8_t quality = 0;  ///< core::quality::Quality
    std::string samples;       ///< encode_samples()
};

struct JournalStats {
    std::uint64_t entries = 0;
    std::uint64_t bytes = 0;    ///< on disk: the database, its WAL and its reserve
    std::uint64_t dropped = 0;  ///< entries dropped for the bound or a full disk, since open
    std::optional<std::int64_t> oldest_timestamp_ms;
};

class Journal {
public:
    /// Opens `options.path`, or creates it. A damaged file is set aside and a new one created;
    /// `set_aside` then says what happened (empty otherwise). Throws std::runtime_error only when
    /// no journal can be created at all (a directory that cannot be written).
    static std::unique_ptr<Journal> open(const JournalOptions& options, std::string& set_aside);
    /// Checkpoints what is written, durably.
    ~Journal();
    Journal(const Journal&) = delete;
    Journal& operator=(const Journal&) = delete;

    /// Gives `entries` their ids and writes them, in order, in transactions of a bounded size;
    /// `durable` also syncs them to the disk (they survive a power loss). Makes room first when
    /// they would pass the bound, and when the disk is full: the oldest entries go, these stay
    /// (one that cannot fit even so is dropped and counted, never thrown).
    void write(std::span<JournalEntry> entries, bool durable);
    /// Up to `limit` entries after `after_id`, oldest first.
    std::vector<JournalEntry> oldest(std::size_t limit, std::uint64_t after_id = 0);
    /// Deletes entries (the broker acknowledged their replay); on a full disk as well.
    void remove(std::span<const std::uint64_t> ids);
    /// Deletes every entry up to `last_id`, that one included.
    void remove_through(std::uint64_t last_id);
    JournalStats stats();
    /// The id of the last entry written (0: none yet).
    std::uint64_t last_id() const;

private:
    struct Db;
    Journal(std::unique_ptr<Db> db, JournalOptions options,
            std::unique_ptr<detail::Reserve> reserve);

    /// Writes `chunk` in one transaction, making room as it must; what cannot fit even so is
    /// dropped and counted.
    void write_chunk(std::span<const JournalEntry> chunk, std::uint64_t bytes);
    /// SQLITE_OK, or the failure's code (the transaction rolled back).
    int insert(std::span<const JournalEntry> chunk);
    /// After SQLITE_FULL: the open transaction is rolled back, the reserve given up, the WAL
    /// checkpointed and cut to nothing, with `drop` some of the oldest entries deleted, the
    /// free pages given back to the filesystem, then the plan made again and the reserve taken
    /// back.
    void recover_from_full(bool drop);
    /// Drops the oldest entries until `bytes` more fit in the database's share.
    void keep_bound(std::uint64_t bytes);
    /// How many of the oldest entries one DELETE drops: about a chunk's worth.
    std::uint64_t drop_step();
    bool drop_oldest(std::uint64_t count);
    /// Gives the database's free pages back to the filesystem, a chunk at a time.
    void give_back();
    /// Runs `attempt` (it returns an SQLite result code) again after making room, as long as
    /// it fails with SQLITE_FULL, a few times; `drop`: the oldest entries may go from the
    /// first time (otherwise from the second).
    template <class F>
    int with_room(F&& attempt, bool drop);
    /// Measures the filesystem and the journal's files again and applies the new plan.
    void plan();
    void checkpoint(int mode);
    std::uint64_t used_bytes();
    std::uint64_t file_bytes();
    void recount();

    std::unique_ptr<Db> db_;
    JournalOptions options_;
    std::unique_ptr<detail::Reserve> reserve_;
    std::unique_ptr<detail::SpacePlan> plan_;
    std::uint64_t page_size_ = 4096;
    std::uint64_t dropped_ = 0;
};

}  // namespace eip2mqtt::adapters::history
