// SQLite loaded on first use: every function the journal calls is found in the library the
// build named, once, and a call through the table reaches SQLite.

#include "adapters/history/detail/sqlite_library.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::adapters::history::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(SqliteLibrary, TheSonameIsSqlites) {
    EXPECT_EQ(std::string(sqlite_soname()).rfind("libsqlite3.so.", 0), 0u) << sqlite_soname();
}

TEST(SqliteLibrary, EveryFunctionTheJournalCallsIsResolvedOnce) {
    const SqliteLibrary& library = sqlite();
    EXPECT_EQ(&library, &sqlite());
#define EIP2MQTT_SQLITE_CHECK(name) \
    EXPECT_NE(reinterpret_cast<const void*>(library.name), nullptr) << #name;
    EIP2MQTT_SQLITE_FUNCTIONS(EIP2MQTT_SQLITE_CHECK)
#undef EIP2MQTT_SQLITE_CHECK
}

TEST(SqliteLibrary, ACallThroughTheTableReachesSqlite) {
    const SqliteLibrary& library = sqlite();
    sqlite3* db = nullptr;
    ASSERT_EQ(library.open_v2(":memory:", &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr),
              SQLITE_OK);
    EXPECT_EQ(library.exec(db, "CREATE TABLE t(x INTEGER)", nullptr, nullptr, nullptr), SQLITE_OK);
    EXPECT_NE(library.exec(db, "CREATE TABLE t(x INTEGER)", nullptr, nullptr, nullptr), SQLITE_OK);
    EXPECT_EQ(std::string(library.errmsg(db)), "table t already exists");
    library.close(db);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::history::detail
