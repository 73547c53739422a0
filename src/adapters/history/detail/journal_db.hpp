#pragma once
// The journal's SQLite connection and its statements (journal_open.cpp opens it).

#include <sqlite3.h>

#include <cstdint>
#include <memory>
#include <string>

#include "adapters/history/detail/sqlite.hpp"
#include "eip2mqtt/adapters/history/journal.hpp"

namespace eip2mqtt::adapters::history {

struct Journal::Db {
    sqlite3* db = nullptr;
    std::unique_ptr<detail::Statement> insert, select_after, remove, remove_through, oldest_time,
        drop_oldest;
    std::uint64_t entries = 0;
    std::uint64_t next_id = 1;

    /// Opens `path` as a journal of ours, or creates it. Throws detail::SqliteError, or
    /// std::runtime_error for a database of another application.
    explicit Db(const std::string& path);
    ~Db();
    Db(const Db&) = delete;
    Db& operator=(const Db&) = delete;

private:
    void prepare();
    void close();
};

}  // namespace eip2mqtt::adapters::history
