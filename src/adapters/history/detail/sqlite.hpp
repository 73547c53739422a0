#pragma once
// SQLite as the journal uses it: prepared statements, errors that keep SQLite's code (a full
// disk is handled, anything else reported), and the few helpers every query needs.

#include <sqlite3.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "adapters/history/detail/sqlite_library.hpp"

namespace eip2mqtt::adapters::history::detail {

/// An SQLite failure with its (extended) result code.
class SqliteError : public std::runtime_error {
public:
    SqliteError(int code, const std::string& what) : std::runtime_error(what), code_(code) {}
    int code() const { return code_; }
    /// SQLITE_FULL: the disk or the page limit. The journal makes room and goes on.
    bool full() const { return (code_ & 0xff) == SQLITE_FULL; }

private:
    int code_;
};

/// Throws the connection's last error as an SqliteError.
[[noreturn]] void fail(sqlite3* db, int code);

class Statement {
public:
    Statement(sqlite3* db, const char* sql);
    ~Statement() { sqlite().finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;
    sqlite3_stmt* get() const { return stmt_; }
    /// Ready for the next use, bindings cleared.
    sqlite3_stmt* fresh() const {
        sqlite().reset(stmt_);
        sqlite().clear_bindings(stmt_);
        return stmt_;
    }

private:
    sqlite3_stmt* stmt_ = nullptr;
};

/// Runs `sql` to its end; returns SQLite's result code (SQLITE_OK on success).
int run(sqlite3* db, const char* sql);
/// The same, throwing an SqliteError on failure.
void exec(sqlite3* db, const char* sql);
void exec(sqlite3* db, const std::string& sql);
/// The first column of the first row of `sql`.
std::int64_t query_int(sqlite3* db, const char* sql);
/// Ends the open transaction, if any, without its changes.
void rollback(sqlite3* db);

}  // namespace eip2mqtt::adapters::history::detail
