// The journal on SQLite: one table of entries whose ids never come back within a process (a
// replay resumes after the last id it saw, across deletions): the journal numbers them itself,
// from the largest in the file. WAL mode with synchronous=NORMAL (a commit is write()s, a
// checkpoint the fsync). Opening is in journal_open.cpp; the room on disk in detail/disk_room.

#include "eip2mqtt/adapters/history/journal.hpp"

#include <algorithm>
#include <filesystem>

#include "adapters/history/detail/disk_room.hpp"
#include "adapters/history/detail/journal_db.hpp"

namespace eip2mqtt::adapters::history {
namespace {

using detail::exec;
using detail::query_int;

/// A row's bytes beyond its payload: its header, key and cell pointer, rounded up.
constexpr std::uint64_t row_overhead = 48;
/// Times a write makes room after SQLITE_FULL before it gives up on what it writes.
constexpr int room_attempts = 4;

std::uint64_t row_bytes(const JournalEntry& entry) {
    return entry.exchange.size() + entry.samples.size() + row_overhead;
}

bool is_full(int code) { return (code & 0xff) == SQLITE_FULL; }

std::string column_text(sqlite3_stmt* stmt, int column) {
    const auto* text = reinterpret_cast<const char*>(detail::sqlite().column_text(stmt, column));
    return text == nullptr ? std::string()
                           : std::string(text, detail::sqlite().column_bytes(stmt, column));
}

std::string column_blob(sqlite3_stmt* stmt, int column) {
    const auto* blob = static_cast<const char*>(detail::sqlite().column_blob(stmt, column));
    return blob == nullptr ? std::string()
                           : std::string(blob, detail::sqlite().column_bytes(stmt, column));
}

/// Runs `step` (one statement, stepped and reset) for each of `items` in one transaction, and
/// commits; the first that does not answer SQLITE_DONE rolls them all back, so a full disk
/// never leaves half a batch.
template <class Items, class Step>
int each_in_transaction(sqlite3* db, const Items& items, Step&& step) {
    if (const int rc = detail::run(db, "BEGIN"); rc != SQLITE_OK) return rc;
    for (const auto& item : items) {
        if (const int rc = step(item); rc != SQLITE_DONE) {
            detail::rollback(db);
            return rc;
        }
    }
    const int rc = detail::run(db, "COMMIT");
    if (rc != SQLITE_OK) detail::rollback(db);
    return rc;
}

}  // namespace

Journal::Journal(std::unique_ptr<Db> db, JournalOptions options,
                 std::unique_ptr<detail::Reserve> reserve)
    : db_(std::move(db)),
      options_(std::move(options)),
      reserve_(std::move(reserve)),
      plan_(std::make_unique<detail::SpacePlan>()) {
    page_size_ = static_cast<std::uint64_t>(query_int(db_->db, "PRAGMA page_size"));
    plan();
}

Journal::~Journal() {
    // A checkpoint syncs the WAL first: every commit so far is on the disk after it.
    checkpoint(SQLITE_CHECKPOINT_PASSIVE);
}

void Journal::plan() {
    auto directory = std::filesystem::path(options_.path).parent_path().string();
    if (directory.empty()) directory = ".";
    *plan_ = detail::plan_space(options_.max_bytes,
                                detail::room_on_disk(directory, file_bytes(), options_.max_bytes),
                                page_size_);
    // The database may not grow past its share (SQLITE_FULL then, as on a full disk); one
    // larger than that keeps its size, and its free pages are used again.
    exec(db_->db, "PRAGMA max_page_count=" +
                      std::to_string(std::max<std::uint64_t>(1, plan_->database / page_size_)));
    exec(db_->db, "PRAGMA wal_autocheckpoint=" + std::to_string(plan_->wal / page_size_));
    exec(db_->db, "PRAGMA journal_size_limit=" + std::to_string(plan_->wal_slot));
    reserve_->hold(plan_->reserve);
}

void Journal::write(std::span<JournalEntry> entries, bool durable) {
    for (auto& entry : entries) entry.id = db_->next_id++;
    // In chunks: one transaction's pages all go to the WAL before its checkpoint, so its size
    // is what keeps the WAL within its share, however many entries a slow moment piled up.
    std::size_t first = 0;
    while (first < entries.size()) {
        std::size_t end = first;
        std::uint64_t bytes = 0;
        do {
            bytes += row_bytes(entries[end++]);
        } while (end < entries.size() && bytes + row_bytes(entries[end]) <= plan_->chunk);
        write_chunk(entries.subspan(first, end - first), bytes);
        first = end;
    }
    if (durable) {
        checkpoint(SQLITE_CHECKPOINT_PASSIVE);
        plan();  // the filesystem's room may have changed
    }
}

void Journal::write_chunk(std::span<const JournalEntry> chunk, std::uint64_t bytes) {
    keep_bound(bytes);
    const int rc = with_room([&] { return insert(chunk); }, true);
    if (rc == SQLITE_OK) {
        db_->entries += chunk.size();
        return;
    }
    if (!is_full(rc)) detail::fail(db_->db, rc);
    if (chunk.size() > 1) {  // halves may fit where the whole did not
        const auto half = chunk.size() / 2;
        write_chunk(chunk.first(half), bytes / 2);
        write_chunk(chunk.subspan(half), bytes - bytes / 2);
        return;
    }
    ++dropped_;  // no room for this one even with the oldest gone
}

int Journal::insert(std::span<const JournalEntry> chunk) {
    return each_in_transaction(db_->db, chunk, [this](const JournalEntry& entry) {
        auto* stmt = db_->insert->fresh();
        detail::sqlite().bind_text(stmt, 1, entry.exchange.data(),
                                   static_cast<int>(entry.exchange.size()), SQLITE_STATIC);
        detail::sqlite().bind_int64(stmt, 2, static_cast<sqlite3_int64>(entry.layout));
        detail::sqlite().bind_int64(stmt, 3, entry.timestamp_ms);
        detail::sqlite().bind_int(stmt, 4, entry.quality);
        detail::sqlite().bind_blob(stmt, 5, entry.samples.data(),
                                   static_cast<int>(entry.samples.size()), SQLITE_STATIC);
        detail::sqlite().bind_int64(stmt, 6, static_cast<sqlite3_int64>(entry.id));
        const int rc = detail::sqlite().step(stmt);
        detail::sqlite().reset(stmt);
        return rc;
    });
}

template <class F>
int Journal::with_room(F&& attempt, bool drop) {
    int rc = attempt();
    for (int i = 0; i < room_attempts && is_full(rc); ++i) {
        recover_from_full(drop || i > 0);
        rc = attempt();
    }
    return rc;
}

void Journal::recover_from_full(bool drop) {
    detail::rollback(db_->db);
    // With the reserve's blocks free, the checkpoint can extend the database with what the
    // WAL holds, and the WAL take the DELETE; TRUNCATE gives the WAL's blocks back after.
    reserve_->release();
    checkpoint(SQLITE_CHECKPOINT_TRUNCATE);
    if (drop) drop_oldest(drop_step());
    give_back();
    recount();
    plan();  // what the disk has now, and the reserve taken again
}

void Journal::keep_bound(std::uint64_t bytes) {
    // Pages in use, not the file's size: the pages of deleted rows are used again. A margin
    // for the pages' own fill (the page limit, plan(), is what the bound rests on), and a
    // thirty-second of the share more, so that the bound is not met again at the next write.
    const auto needed = 2 * bytes + page_size_;
    if (db_->entries == 0 || used_bytes() + needed <= plan_->database) return;
    const auto target = plan_->database - std::min(plan_->database, plan_->database / 32);
    for (int i = 0; i < 1024 && db_->entries > 0 && used_bytes() + needed > target; ++i) {
        if (!drop_oldest(drop_step())) return;  // the write's own recovery takes over
    }
    // The database's file is larger than its share (the disk shrank, or it was full).
    if (detail::file_bytes(options_.path) > plan_->database) give_back();
}

std::uint64_t Journal::drop_step() {
    // About a chunk's worth of entries: a DELETE's pages go through the WAL like an insert's.
    const auto per_entry =
        std::max<std::uint64_t>(1, used_bytes() / std::max<std::uint64_t>(1, db_->entries));
    return std::clamp<std::uint64_t>(plan_->chunk / per_entry, 1,
                                     std::max<std::uint64_t>(1, db_->entries / 10));
}

void Journal::give_back() {
    // A chunk's worth of free pages at a time, moved to the end of the file and cut off by
    // the checkpoint, which gives the WAL's blocks back as well.
    const auto step = std::to_string(std::max<std::uint64_t>(1, plan_->chunk / page_size_));
    const auto sql = "PRAGMA incremental_vacuum(" + step + ")";
    for (int i = 0; i < 4096 && query_int(db_->db, "PRAGMA freelist_count") > 0; ++i) {
        if (detail::run(db_->db, sql.c_str()) != SQLITE_OK) break;
        checkpoint(SQLITE_CHECKPOINT_TRUNCATE);
    }
    checkpoint(SQLITE_CHECKPOINT_TRUNCATE);
}

bool Journal::drop_oldest(std::uint64_t count) {
    auto* stmt = db_->drop_oldest->fresh();
    detail::sqlite().bind_int64(stmt, 1, static_cast<sqlite3_int64>(count));
    const int rc = detail::sqlite().step(stmt);
    const auto removed = static_cast<std::uint64_t>(detail::sqlite().changes(db_->db));
    detail::sqlite().reset(stmt);
    if (rc != SQLITE_DONE) {
        detail::rollback(db_->db);
        return false;
    }
    db_->entries -= std::min(db_->entries, removed);
    dropped_ += removed;
    return true;
}

void Journal::checkpoint(int mode) {
    detail::sqlite().wal_checkpoint_v2(db_->db, nullptr, mode, nullptr, nullptr);
}

std::uint64_t Journal::used_bytes() {
    return static_cast<std::uint64_t>(query_int(db_->db, "PRAGMA page_count") -
                                      query_int(db_->db, "PRAGMA freelist_count")) *
           page_size_;
}

std::uint64_t Journal::file_bytes() {
    return detail::file_bytes(options_.path) + detail::file_bytes(options_.path + "-wal") +
           reserve_->held();
}

void Journal::recount() {
    db_->entries = static_cast<std::uint64_t>(query_int(db_->db, "SELECT count(*) FROM entries"));
}

std::vector<JournalEntry> Journal::oldest(std::size_t limit, std::uint64_t after_id) {
    std::vector<JournalEntry> out;
    auto* stmt = db_->select_after->fresh();
    detail::sqlite().bind_int64(stmt, 1, static_cast<sqlite3_int64>(after_id));
    detail::sqlite().bind_int64(stmt, 2, static_cast<sqlite3_int64>(limit));
    while (detail::sqlite().step(stmt) == SQLITE_ROW) {
        JournalEntry entry;
        entry.id = static_cast<std::uint64_t>(detail::sqlite().column_int64(stmt, 0));
        entry.exchange = column_text(stmt, 1);
        entry.layout = static_cast<std::uint64_t>(detail::sqlite().column_int64(stmt, 2));
        entry.timestamp_ms = detail::sqlite().column_int64(stmt, 3);
        entry.quality = static_cast<std::uint8_t>(detail::sqlite().column_int(stmt, 4));
        entry.samples = column_blob(stmt, 5);
        out.push_back(std::move(entry));
    }
    detail::sqlite().reset(stmt);
    return out;
}

void Journal::remove(std::span<const std::uint64_t> ids) {
    auto* db = db_->db;
    std::uint64_t removed = 0;
    const int rc = with_room(
        [&] {
            removed = 0;
            return each_in_transaction(db, ids, [&](std::uint64_t id) {
                auto* stmt = db_->remove->fresh();
                detail::sqlite().bind_int64(stmt, 1, static_cast<sqlite3_int64>(id));
                const int rc = detail::sqlite().step(stmt);
                removed += static_cast<std::uint64_t>(detail::sqlite().changes(db));
                detail::sqlite().reset(stmt);
                return rc;
            });
        },
        false);
    if (rc != SQLITE_OK) detail::fail(db, rc);
    db_->entries -= std::min(db_->entries, removed);
}

void Journal::remove_through(std::uint64_t last_id) {
    auto* db = db_->db;
    std::uint64_t removed = 0;
    const int rc = with_room(
        [&] {
            auto* stmt = db_->remove_through->fresh();
            detail::sqlite().bind_int64(stmt, 1, static_cast<sqlite3_int64>(last_id));
            const int step = detail::sqlite().step(stmt);
            removed = static_cast<std::uint64_t>(detail::sqlite().changes(db));
            detail::sqlite().reset(stmt);
            return step == SQLITE_DONE ? SQLITE_OK : step;
        },
        false);
    if (rc != SQLITE_OK) detail::fail(db, rc);
    db_->entries -= std::min(db_->entries, removed);
}

std::uint64_t Journal::last_id() const { return db_->next_id - 1; }

JournalStats Journal::stats() {
    JournalStats stats;
    stats.entries = db_->entries;
    stats.dropped = dropped_;
    stats.bytes = file_bytes();
    auto* stmt = db_->oldest_time->fresh();
    if (detail::sqlite().step(stmt) == SQLITE_ROW)
        stats.oldest_timestamp_ms = detail::sqlite().column_int64(stmt, 0);
    detail::sqlite().reset(stmt);
    return stats;
}

}  // namespace eip2mqtt::adapters::history
