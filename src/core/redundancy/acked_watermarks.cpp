#include "eip2mqtt/core/redundancy/acked_watermarks.hpp"

#include <bit>

namespace eip2mqtt::core::redundancy {

AckedWatermarks::AckedWatermarks(std::size_t remembered)
    : awaiting_(std::bit_ceil(remembered == 0 ? std::size_t{1} : remembered)) {}

std::uint64_t AckedWatermarks::published(std::uint32_t exchange, const SampleKey& key) {
    const auto serial = ++last_serial_;
    awaiting_[serial & (awaiting_.size() - 1)] = {serial, exchange, key};
    return token_bit | serial;
}

void AckedWatermarks::acknowledged(std::uint64_t token) {
    const auto serial = token & ~token_bit;
    const auto& publication = awaiting_[serial & (awaiting_.size() - 1)];
    // Overwritten by a later publication, or forgotten by clear(): nothing to say any more.
    if (!owns(token) || serial == 0 || publication.serial != serial) return;
    auto& mark = marks_[publication.exchange];
    if (serial > mark.serial) mark = {serial, publication.key};
}

void AckedWatermarks::start_at(std::uint32_t exchange, const SampleKey& key) {
    marks_.insert_or_assign(exchange, Mark{0, key});
}

void AckedWatermarks::forget(std::uint32_t exchange) {
    marks_.erase(exchange);
    for (auto& publication : awaiting_) {
        if (publication.exchange == exchange) publication = {};
    }
}

void AckedWatermarks::clear() {
    marks_.clear();
    for (auto& publication : awaiting_) publication = {};
}

std::optional<SampleKey> AckedWatermarks::watermark(std::uint32_t exchange) const {
    const auto mark = marks_.find(exchange);
    if (mark == marks_.end()) return std::nullopt;
    return mark->second.key;
}

}  // namespace eip2mqtt::core::redundancy
