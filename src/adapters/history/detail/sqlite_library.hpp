#pragma once
/// SQLite, loaded when the first journal is opened (dlopen) rather than with the binary.
///
/// Only `mqtt.store_and_forward` journals. Linked at start, libsqlite3 would be mapped,
/// relocated and partly resident in every gateway for nothing: about 0.25 MB of its resident
/// memory. Loaded here, it costs that only where a journal is opened. A call through the table
/// costs what a call through the PLT does: one indirect jump.
///
/// Threading: sqlite() may be called from any thread; the table it returns is immutable.

#include <sqlite3.h>

namespace eip2mqtt::adapters::history::detail {

// The SQLite functions the journal calls, without their `sqlite3_` prefix.
// clang-format off
#define EIP2MQTT_SQLITE_FUNCTIONS(X) \
    X(open_v2) X(close) X(errmsg) X(extended_errcode) X(extended_result_codes) X(exec)           \
    X(prepare_v2) X(prepare_v3) X(finalize) X(step) X(reset) X(clear_bindings) X(changes)        \
    X(get_autocommit) X(wal_checkpoint_v2) X(bind_int) X(bind_int64) X(bind_text)                \
    X(bind_blob) X(column_int) X(column_int64) X(column_text) X(column_blob)                     \
    X(column_bytes)
// clang-format on

/// Each function of EIP2MQTT_SQLITE_FUNCTIONS, resolved from the loaded library.
struct SqliteLibrary {
#define EIP2MQTT_SQLITE_MEMBER(name) decltype(&::sqlite3_##name) name;
    EIP2MQTT_SQLITE_FUNCTIONS(EIP2MQTT_SQLITE_MEMBER)
#undef EIP2MQTT_SQLITE_MEMBER
};

/// The library named by sqlite_soname(), loaded on the first call and kept for the process's
/// life. Throws std::runtime_error naming it when it cannot be loaded or lacks a function.
const SqliteLibrary& sqlite();

/// The soname sqlite() loads (the one the build found, e.g. `libsqlite3.so.0`).
const char* sqlite_soname();

}  // namespace eip2mqtt::adapters::history::detail
