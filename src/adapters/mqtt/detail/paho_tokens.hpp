#pragma once
/// What a Paho token says, in our terms: why an operation failed, and the publication or
/// connection it belongs to (ids travel as Paho's user context).
///
/// Module-private (src/adapters/mqtt/detail); pure.

#include <mqtt/async_client.h>

#include <cstdint>
#include <string>

namespace eip2mqtt::adapters::mqtt::detail {

/// Paho's words for a failed operation, with the broker's reason code when it gave one.
std::string describe_failure(const ::mqtt::token& tok);

inline void* to_context(std::uint64_t id) {
    return reinterpret_cast<void*>(static_cast<std::uintptr_t>(id));
}
inline std::uint64_t from_context(void* ctx) { return reinterpret_cast<std::uintptr_t>(ctx); }

}  // namespace eip2mqtt::adapters::mqtt::detail
