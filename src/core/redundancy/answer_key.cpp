#include "eip2mqtt/core/redundancy/answer_key.hpp"

namespace eip2mqtt::core::redundancy {
namespace {

constexpr std::uint64_t fnv_offset = 0xcbf29ce484222325ULL;
constexpr std::uint64_t fnv_prime = 0x100000001b3ULL;

std::uint64_t add(std::uint64_t hash, std::string_view bytes) {
    for (const char c : bytes) {
        hash ^= static_cast<std::uint8_t>(c);
        hash *= fnv_prime;
    }
    return hash;
}

}  // namespace

std::uint64_t answer_key(std::string_view response_topic, std::string_view correlation_data) {
    auto hash = add(fnv_offset, response_topic);
    hash *= fnv_prime;  // the NUL between the two: x ^ 0 == x
    return add(hash, correlation_data);
}

}  // namespace eip2mqtt::core::redundancy
