// The journal on SQLite: one table of entries whose ids never come back within a process (a
// replay resumes after the last id it saw, across deletions): the journal numbers them itself,
// from the largest in the file, which costs SQLite's AUTOINCREMENT bookkeeping on every insert, WAL
// mode with synchronous=NORMAL (a commit is write()s, a checkpoint the fsync), and the file marked
// with our application_id so that another database is never taken for a journal.

#include "eip2mqtt/adapters/history/journal.hpp"

#include <sqlite3.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace eip2mqtt::adapters::history {
namespace {

constexpr int application_id = 0x45495032;  // "EIP2"

class Statement {
public:
    Statement(sqlite3* db, const char* sql) {
        if (sqlite3_prepare_v3(db, sql, -1, SQLITE_PREPARE_PERSISTENT, &stmt_, nullptr) !=
            SQLITE_OK) {
            throw std::runtime_error(std::string("journal: ") + sqlite3_errmsg(db));
        }
    }
    ~Statement() { sqlite3_finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;
    sqlite3_stmt* get() const { return stmt_; }
    /// Ready for the next use, bindings cleared.
    sqlite3_stmt* fresh() const {
        sqlite3_reset(stmt_);
        sqlite3_clear_bindings(stmt_);
        return stmt_;
    }

private:
    sqlite3_stmt* stmt_ = nullptr;
};

void exec(sqlite3* db, const char* sql) {
    char* error = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &error) != SQLITE_OK) {
        std::string text = error != nullptr ? error : sqlite3_errmsg(db);
        sqlite3_free(error);
        throw std::runtime_error("journal: " + text);
    }
}

std::int64_t query_int(sqlite3* db, const char* sql) {
    Statement statement(db, sql);
    if (sqlite3_step(statement.get()) != SQLITE_ROW) {
        throw std::runtime_error(std::string("journal: ") + sqlite3_errmsg(db));
    }
    return sqlite3_column_int64(statement.get(), 0);
}

std::string column_text(sqlite3_stmt* stmt, int column) {
    const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(stmt, column));
    return text == nullptr ? std::string() : std::string(text, sqlite3_column_bytes(stmt, column));
}

std::string column_blob(sqlite3_stmt* stmt, int column) {
    const auto* blob = static_cast<const char*>(sqlite3_column_blob(stmt, column));
    return blob == nullptr ? std::string() : std::string(blob, sqlite3_column_bytes(stmt, column));
}

}  // namespace

struct Journal::Db {
    sqlite3* db = nullptr;
    std::unique_ptr<Statement> insert, select_after, remove, oldest_time, drop_oldest;
    std::uint64_t entries = 0;
    std::uint64_t next_id = 1;

    explicit Db(const std::string& path) {
        if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                            nullptr) != SQLITE_OK) {
            const std::string error = db != nullptr ? sqlite3_errmsg(db) : "out of memory";
            sqlite3_close(db);
            throw std::runtime_error(error);
        }
        try {
            const auto id = query_int(db, "PRAGMA application_id");
            const auto tables = query_int(db, "SELECT count(*) FROM sqlite_schema");
            if (tables > 0 && id != application_id) {
                throw std::runtime_error("not an eip2mqtt journal");
            }
            exec(db, "PRAGMA journal_mode=WAL");
            exec(db, "PRAGMA synchronous=NORMAL");
            exec(db,
                 "CREATE TABLE IF NOT EXISTS entries("
                 " id INTEGER PRIMARY KEY, exchange TEXT NOT NULL,"
                 " layout INTEGER NOT NULL, timestamp_ms INTEGER NOT NULL,"
                 " quality INTEGER NOT NULL, samples BLOB NOT NULL)");
            exec(db, ("PRAGMA application_id=" + std::to_string(application_id)).c_str());
            insert = std::make_unique<Statement>(
                db,
                "INSERT INTO entries(exchange, layout, timestamp_ms, quality, samples, id)"
                " VALUES(?, ?, ?, ?, ?, ?)");
            select_after = std::make_unique<Statement>(
                db,
                "SELECT id, exchange, layout, timestamp_ms, quality, samples FROM entries"
                " WHERE id > ? ORDER BY id LIMIT ?");
            remove = std::make_unique<Statement>(db, "DELETE FROM entries WHERE id = ?");
            oldest_time = std::make_unique<Statement>(
                db, "SELECT timestamp_ms FROM entries ORDER BY id LIMIT 1");
            drop_oldest = std::make_unique<Statement>(
                db, "DELETE FROM entries WHERE id IN (SELECT id FROM entries ORDER BY id LIMIT ?)");
            // Reads every page of the table: a damaged file shows here, not in the middle of a
            // replay. (Counting is also what stats() starts from.)
            entries = static_cast<std::uint64_t>(query_int(db, "SELECT count(*) FROM entries"));
            next_id = static_cast<std::uint64_t>(
                          query_int(db, "SELECT coalesce(max(id), 0) FROM entries")) +
                      1;
        } catch (...) {
            insert.reset();
            select_after.reset();
            remove.reset();
            oldest_time.reset();
            drop_oldest.reset();
            sqlite3_close(db);
            throw;
        }
    }
    ~Db() {
        insert.reset();
        select_after.reset();
        remove.reset();
        oldest_time.reset();
        drop_oldest.reset();
        sqlite3_close(db);
    }
};

std::unique_ptr<Journal> Journal::open(const JournalOptions& options, std::string& set_aside) {
    set_aside.clear();
    try {
        return std::unique_ptr<Journal>(new Journal(std::make_unique<Db>(options.path), options));
    } catch (const std::exception& e) {
        const auto stamp = std::chrono::duration_cast<std::chrono::seconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
        const auto aside = options.path + ".damaged-" + std::to_string(stamp);
        std::error_code ec;
        std::filesystem::rename(options.path, aside, ec);
        if (ec) throw std::runtime_error("journal " + options.path + ": " + e.what());
        for (const auto* suffix : {"-wal", "-shm"}) {
            std::filesystem::remove(options.path + suffix, ec);
        }
        set_aside = "journal " + options.path + " cannot be read (" + e.what() +
                    "): set aside as " + aside + ", a new one started";
    }
    return std::unique_ptr<Journal>(new Journal(std::make_unique<Db>(options.path), options));
}

Journal::Journal(std::unique_ptr<Db> db, JournalOptions options)
    : db_(std::move(db)), options_(std::move(options)) {
    // The bound covers the WAL too: a sixteenth of it, checkpointed into the file when full and
    // cut back to that size after, the rest for the entries themselves.
    const auto page = static_cast<std::uint64_t>(query_int(db_->db, "PRAGMA page_size"));
    const auto wal = options_.max_bytes / 16;
    exec(db_->db,
         ("PRAGMA wal_autocheckpoint=" + std::to_string(std::max<std::uint64_t>(1, wal / page)))
             .c_str());
    exec(db_->db, ("PRAGMA journal_size_limit=" + std::to_string(wal)).c_str());
    table_bound_ = options_.max_bytes - wal;
    if (options_.disk_full_after_pages > 0) {
        exec(db_->db,
             ("PRAGMA max_page_count=" + std::to_string(options_.disk_full_after_pages)).c_str());
    }
}

Journal::~Journal() {
    try {
        commit(true);
    } catch (const std::exception&) {
    }
}

void Journal::append(JournalEntry& entry) {
    if (!in_transaction_) {
        exec(db_->db, "BEGIN");
        in_transaction_ = true;
    }
    auto* stmt = db_->insert->fresh();
    sqlite3_bind_text(stmt, 1, entry.exchange.data(), static_cast<int>(entry.exchange.size()),
                      SQLITE_STATIC);
    sqlite3_bind_int64(stmt, 2, static_cast<sqlite3_int64>(entry.layout));
    sqlite3_bind_int64(stmt, 3, entry.timestamp_ms);
    sqlite3_bind_int(stmt, 4, entry.quality);
    sqlite3_bind_blob(stmt, 5, entry.samples.data(), static_cast<int>(entry.samples.size()),
                      SQLITE_STATIC);
    entry.id = db_->next_id++;
    sqlite3_bind_int64(stmt, 6, static_cast<sqlite3_int64>(entry.id));
    const int rc = sqlite3_step(stmt);
    sqlite3_reset(stmt);
    if (rc == SQLITE_FULL) {
        // No room even in the transaction: make some, and try once more. The entries of the
        // transaction so far are lost with it: counted as dropped.
        rollback();
        drop_oldest(std::max<std::uint64_t>(1, db_->entries / 10));
        exec(db_->db, "BEGIN");
        in_transaction_ = true;
        if (sqlite3_step(db_->insert->get()) != SQLITE_DONE) {
            sqlite3_reset(db_->insert->get());
            ++dropped_;
            return;
        }
        sqlite3_reset(db_->insert->get());
    } else if (rc != SQLITE_DONE) {
        throw std::runtime_error(std::string("journal: ") + sqlite3_errmsg(db_->db));
    }
    ++db_->entries;
    ++in_transaction_entries_;
}

void Journal::rollback() {
    sqlite3_exec(db_->db, "ROLLBACK", nullptr, nullptr, nullptr);
    in_transaction_ = false;
    db_->entries -= std::min(db_->entries, in_transaction_entries_);
    dropped_ += in_transaction_entries_;
    in_transaction_entries_ = 0;
}

void Journal::commit(bool durable) {
    if (in_transaction_) {
        if (sqlite3_exec(db_->db, "COMMIT", nullptr, nullptr, nullptr) == SQLITE_OK) {
            in_transaction_ = false;
            in_transaction_entries_ = 0;
        } else {
            const bool full = sqlite3_errcode(db_->db) == SQLITE_FULL;
            const std::string error = sqlite3_errmsg(db_->db);
            rollback();
            if (!full) throw std::runtime_error("journal: " + error);
            drop_oldest(std::max<std::uint64_t>(1, db_->entries / 10));
        }
    }
    if (durable) {
        // A checkpoint syncs the WAL first: every commit so far is on the disk after it.
        sqlite3_wal_checkpoint_v2(db_->db, nullptr, SQLITE_CHECKPOINT_PASSIVE, nullptr, nullptr);
    }
    enforce_bound();
}

void Journal::enforce_bound() {
    // Pages in use, not the file's size: deleted rows leave free pages that SQLite reuses.
    for (;;) {
        const auto used = static_cast<std::uint64_t>((query_int(db_->db, "PRAGMA page_count") -
                                                      query_int(db_->db, "PRAGMA freelist_count")) *
                                                     query_int(db_->db, "PRAGMA page_size"));
        if (used <= table_bound_ || db_->entries == 0) return;
        drop_oldest(std::max<std::uint64_t>(1, db_->entries / 10));
    }
}

void Journal::drop_oldest(std::uint64_t count) {
    auto* stmt = db_->drop_oldest->fresh();
    sqlite3_bind_int64(stmt, 1, static_cast<sqlite3_int64>(count));
    sqlite3_step(stmt);
    const auto removed = static_cast<std::uint64_t>(sqlite3_changes(db_->db));
    sqlite3_reset(stmt);
    db_->entries -= std::min(db_->entries, removed);
    dropped_ += removed;
}

std::vector<JournalEntry> Journal::oldest(std::size_t limit, std::uint64_t after_id) {
    std::vector<JournalEntry> out;
    auto* stmt = db_->select_after->fresh();
    sqlite3_bind_int64(stmt, 1, static_cast<sqlite3_int64>(after_id));
    sqlite3_bind_int64(stmt, 2, static_cast<sqlite3_int64>(limit));
    while (sqlite3_step(stmt) == SQLITE_ROW) {
        JournalEntry entry;
        entry.id = static_cast<std::uint64_t>(sqlite3_column_int64(stmt, 0));
        entry.exchange = column_text(stmt, 1);
        entry.layout = static_cast<std::uint64_t>(sqlite3_column_int64(stmt, 2));
        entry.timestamp_ms = sqlite3_column_int64(stmt, 3);
        entry.quality = static_cast<std::uint8_t>(sqlite3_column_int(stmt, 4));
        entry.samples = column_blob(stmt, 5);
        out.push_back(std::move(entry));
    }
    sqlite3_reset(stmt);
    return out;
}

void Journal::remove(std::span<const std::uint64_t> ids) {
    const bool own = !in_transaction_;
    if (own) exec(db_->db, "BEGIN");
    for (const auto id : ids) {
        auto* stmt = db_->remove->fresh();
        sqlite3_bind_int64(stmt, 1, static_cast<sqlite3_int64>(id));
        sqlite3_step(stmt);
        db_->entries -= std::min<std::uint64_t>(db_->entries, sqlite3_changes(db_->db));
        sqlite3_reset(stmt);
    }
    if (own) exec(db_->db, "COMMIT");
}

JournalStats Journal::stats() {
    JournalStats stats;
    stats.entries = db_->entries;
    stats.dropped = dropped_;
    std::error_code ec;
    for (const auto* suffix : {"", "-wal"}) {
        const auto size = std::filesystem::file_size(options_.path + suffix, ec);
        if (!ec) stats.bytes += size;
    }
    auto* stmt = db_->oldest_time->fresh();
    if (sqlite3_step(stmt) == SQLITE_ROW) stats.oldest_timestamp_ms = sqlite3_column_int64(stmt, 0);
    sqlite3_reset(stmt);
    return stats;
}

}  // namespace eip2mqtt::adapters::history
