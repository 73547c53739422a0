#include "adapters/history/detail/sqlite_library.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace eip2mqtt::adapters::history::detail {
namespace {

[[noreturn]] void fail(const std::string& what) {
    const char* reason = ::dlerror();
    throw std::runtime_error("journal: " + what +
                             (reason != nullptr ? std::string(": ") + reason : std::string()));
}

template <typename Function>
void resolve(void* library, const char* name, Function& function) {
    function = reinterpret_cast<Function>(::dlsym(library, name));
    if (function == nullptr) fail(std::string(sqlite_soname()) + " lacks " + name);
}

SqliteLibrary load() {
    void* library = ::dlopen(sqlite_soname(), RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) fail(std::string("cannot load SQLite (") + sqlite_soname() + ")");
    SqliteLibrary sqlite{};
#define EIP2MQTT_SQLITE_RESOLVE(name) resolve(library, "sqlite3_" #name, sqlite.name);
    EIP2MQTT_SQLITE_FUNCTIONS(EIP2MQTT_SQLITE_RESOLVE)
#undef EIP2MQTT_SQLITE_RESOLVE
    return sqlite;  // the library stays loaded: its functions are used until exit
}

}  // namespace

const char* sqlite_soname() { return EIP2MQTT_SQLITE_SONAME; }

const SqliteLibrary& sqlite() {
    static const SqliteLibrary library = load();  // a failed load throws and is tried again
    return library;
}

}  // namespace eip2mqtt::adapters::history::detail
