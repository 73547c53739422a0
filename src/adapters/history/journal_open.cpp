// Opening the journal: the SQLite connection (exclusive, WAL, our application_id), and what is
// done with a file that is not a journal of ours (set aside) or a path that is a symbolic link
// (never followed: set aside as well).

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "adapters/history/detail/disk_room.hpp"
#include "adapters/history/detail/journal_db.hpp"

namespace eip2mqtt::adapters::history {
namespace {

using detail::exec;
using detail::query_int;
using detail::Statement;

constexpr int application_id = 0x45495032;  // "EIP2"
constexpr int auto_vacuum_incremental = 2;

/// Failures that say nothing about the file: it is not set aside for them.
bool says_nothing_of_the_file(int code) {
    const int primary = code & 0xff;
    return primary == SQLITE_FULL || primary == SQLITE_BUSY || primary == SQLITE_LOCKED ||
           primary == SQLITE_NOMEM;
}

/// Why `path` is not taken as a journal before SQLite opens it (empty: it may be).
std::string refused_path(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec))) return {};
    const auto target = std::filesystem::read_symlink(path, ec);
    return "a symbolic link (to " + target.string() + "), not followed";
}

/// A WAL or rollback journal beside the journal that is a symbolic link was never made by
/// SQLite for us: the link is removed, and nothing it points to is touched.
void remove_linked_companions(const std::string& path) {
    for (const auto* suffix : {"-wal", "-shm", "-journal"}) {
        const auto companion = path + suffix;
        struct stat st {};
        if (::lstat(companion.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
            ::unlink(companion.c_str());
        }
    }
}

}  // namespace

Journal::Db::Db(const std::string& path) {
    const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOFOLLOW;
    if (const int rc = detail::sqlite().open_v2(path.c_str(), &db, flags, nullptr);
        rc != SQLITE_OK) {
        const int code = db != nullptr ? detail::sqlite().extended_errcode(db) : rc;
        const std::string error = db != nullptr ? detail::sqlite().errmsg(db) : "out of memory";
        detail::sqlite().close(db);
        throw detail::SqliteError(code, error);
    }
    detail::sqlite().extended_result_codes(db, 1);
    try {
        // Before the first read: the lock is held until close, and the WAL's index lives in
        // memory, so no `-shm` file needs room on the disk.
        exec(db, "PRAGMA locking_mode=EXCLUSIVE");
        const auto id = query_int(db, "PRAGMA application_id");
        const auto tables = query_int(db, "SELECT count(*) FROM sqlite_schema");
        if (tables > 0 && id != application_id) {
            throw std::runtime_error("not an eip2mqtt journal");
        }
        // Pages of dropped entries can then be given back to a full disk.
        if (tables == 0) exec(db, "PRAGMA auto_vacuum=INCREMENTAL");
        exec(db, "PRAGMA journal_mode=WAL");
        exec(db, "PRAGMA synchronous=NORMAL");
        exec(db,
             "CREATE TABLE IF NOT EXISTS entries("
             " id INTEGER PRIMARY KEY, exchange TEXT NOT NULL,"
             " layout INTEGER NOT NULL, timestamp_ms INTEGER NOT NULL,"
             " quality INTEGER NOT NULL, samples BLOB NOT NULL)");
        // Written only when it changes: a journal opened on a full disk writes nothing.
        if (id != application_id)
            exec(db, "PRAGMA application_id=" + std::to_string(application_id));
        prepare();
        // Reads every page of the table: a damaged file shows here, not in the middle of a
        // replay. (Counting is also what stats() starts from.)
        entries = static_cast<std::uint64_t>(query_int(db, "SELECT count(*) FROM entries"));
        next_id =
            static_cast<std::uint64_t>(query_int(db, "SELECT coalesce(max(id), 0) FROM entries")) +
            1;
        if (entries == 0 && query_int(db, "PRAGMA auto_vacuum") != auto_vacuum_incremental) {
            // An empty journal of an earlier version: made able to give pages back, cheaply.
            exec(db, "PRAGMA auto_vacuum=INCREMENTAL");
            exec(db, "VACUUM");
        }
    } catch (...) {
        close();
        throw;
    }
}

void Journal::Db::prepare() {
    insert = std::make_unique<Statement>(
        db,
        "INSERT INTO entries(exchange, layout, timestamp_ms, quality, samples, id)"
        " VALUES(?, ?, ?, ?, ?, ?)");
    select_after = std::make_unique<Statement>(
        db,
        "SELECT id, exchange, layout, timestamp_ms, quality, samples FROM entries"
        " WHERE id > ? ORDER BY id LIMIT ?");
    remove = std::make_unique<Statement>(db, "DELETE FROM entries WHERE id = ?");
    remove_through = std::make_unique<Statement>(db, "DELETE FROM entries WHERE id <= ?");
    oldest_time =
        std::make_unique<Statement>(db, "SELECT timestamp_ms FROM entries ORDER BY id LIMIT 1");
    drop_oldest = std::make_unique<Statement>(
        db, "DELETE FROM entries WHERE id IN (SELECT id FROM entries ORDER BY id LIMIT ?)");
}

void Journal::Db::close() {
    insert.reset();
    select_after.reset();
    remove.reset();
    remove_through.reset();
    oldest_time.reset();
    drop_oldest.reset();
    detail::sqlite().close(db);
    db = nullptr;
}

Journal::Db::~Db() { close(); }

std::unique_ptr<Journal> Journal::open(const JournalOptions& options, std::string& set_aside) {
    set_aside.clear();
    // Given up first: opening a journal on a full disk may need its room (a WAL to recover).
    auto reserve = std::make_unique<detail::Reserve>(options.path + "-reserve");
    reserve->release();
    remove_linked_companions(options.path);
    auto problem = refused_path(options.path);
    if (problem.empty()) {
        try {
            auto db = std::make_unique<Db>(options.path);  // before the reserve is handed over
            return std::unique_ptr<Journal>(
                new Journal(std::move(db), options, std::move(reserve)));
        } catch (const detail::SqliteError& e) {
            if (says_nothing_of_the_file(e.code())) {
                throw std::runtime_error("journal " + options.path + ": " + e.what());
            }
            problem = e.what();
        } catch (const std::runtime_error& e) {
            problem = e.what();
        }
    }
    const auto stamp =
        std::chrono::duration_cast<std::chrono::seconds>(options.clock->wall().time_since_epoch())
            .count();
    const auto aside = options.path + ".damaged-" + std::to_string(stamp);
    std::error_code ec;
    std::filesystem::rename(options.path, aside, ec);
    if (ec) throw std::runtime_error("journal " + options.path + ": " + problem);
    for (const auto* suffix : {"-wal", "-shm"}) std::filesystem::remove(options.path + suffix, ec);
    set_aside = "journal " + options.path + " cannot be read (" + problem + "): set aside as " +
                aside + ", a new one started";
    auto db = std::make_unique<Db>(options.path);
    return std::unique_ptr<Journal>(new Journal(std::move(db), options, std::move(reserve)));
}

}  // namespace eip2mqtt::adapters::history
