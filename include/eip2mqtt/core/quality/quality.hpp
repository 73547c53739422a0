#pragma once
/// Tag quality (docs/mqtt-api.md "Tag values"): good; stale once the exchange timed out; bad while
/// the exchange is in signature or length mismatch.

#include <cstdint>
#include <optional>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/exchange/consumed_exchange.hpp"

namespace eip2mqtt::core::quality {

enum class Quality : std::uint8_t { good, stale, bad };

inline constexpr auto quality_names = enum_names<Quality>("good", "stale", "bad");

constexpr std::string_view to_string(Quality quality) { return quality_names.name_of(quality); }

/// The tags' quality in an exchange state; nullopt while waiting (nothing to publish yet).
std::optional<Quality> quality_of(exchange::ConsumeState state);

}  // namespace eip2mqtt::core::quality
