// Fuzzes the YAML configuration loader: any text must yield a config or diagnostics, never an
// exception or a crash. Relative `points:` files resolve under a directory that does not exist.

#include <cstddef>
#include <cstdint>
#include <string>

#include "eip2mqtt/adapters/yaml/load_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const auto result =
        eip2mqtt::adapters::yaml::load_config_text(text, "/nonexistent-eip2mqtt-fuzz/fuzz.yaml");
    if (result) {
        (void)eip2mqtt::core::config::make_plans(result.value());
    } else if (result.error().empty()) {
        __builtin_trap();  // a failure always says why
    }
    return 0;
}
