#include "adapters/history/detail/sqlite.hpp"

namespace eip2mqtt::adapters::history::detail {

void fail(sqlite3* db, int code) {
    throw SqliteError(code, std::string("journal: ") + sqlite().errmsg(db));
}

Statement::Statement(sqlite3* db, const char* sql) {
    const int rc = sqlite().prepare_v3(db, sql, -1, SQLITE_PREPARE_PERSISTENT, &stmt_, nullptr);
    if (rc != SQLITE_OK) fail(db, sqlite().extended_errcode(db));
}

int run(sqlite3* db, const char* sql) {
    // Stepped to the end: some statements (PRAGMA incremental_vacuum) do one unit of work per
    // step, which sqlite3_exec would also do, but without telling the code of a failure apart.
    sqlite3_stmt* stmt = nullptr;
    int rc = sqlite().prepare_v2(db, sql, -1, &stmt, nullptr);
    if (rc != SQLITE_OK) return sqlite().extended_errcode(db);
    do {
        rc = sqlite().step(stmt);
    } while (rc == SQLITE_ROW);
    sqlite().finalize(stmt);
    return rc == SQLITE_DONE ? SQLITE_OK : sqlite().extended_errcode(db);
}

void exec(sqlite3* db, const char* sql) {
    if (const int rc = run(db, sql); rc != SQLITE_OK) fail(db, rc);
}

void exec(sqlite3* db, const std::string& sql) { exec(db, sql.c_str()); }

std::int64_t query_int(sqlite3* db, const char* sql) {
    Statement statement(db, sql);
    const int rc = sqlite().step(statement.get());
    if (rc != SQLITE_ROW) fail(db, sqlite().extended_errcode(db));
    return sqlite().column_int64(statement.get(), 0);
}

void rollback(sqlite3* db) {
    if (sqlite().get_autocommit(db) == 0) sqlite().exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
}

}  // namespace eip2mqtt::adapters::history::detail
