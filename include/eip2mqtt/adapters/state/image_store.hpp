#pragma once
/// Persisted produced images (issue #3): one file per produced exchange in `state_dir`, so a
/// restart keeps producing the last written values rather than zeros. A file is replaced
/// atomically (write a temporary, fsync, rename, fsync the directory), and carries a layout
/// fingerprint: a file written for another layout (length, tag addresses or types) is ignored,
/// so `initial` values apply instead.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::adapters::state {

/// A fingerprint of what the bytes of an image mean: length, and each tag's address and type.
std::uint64_t layout_fingerprint(const core::plan::ExchangePlan& plan);

class ImageStore {
public:
    /// `directory` is created when missing (one level). Nothing is read or written until asked.
    explicit ImageStore(std::string directory);

    /// The image saved for this exchange, when there is one for the same layout; nullopt when
    /// missing, unreadable, corrupt or of another layout (logged once at info or warn).
    std::optional<std::vector<std::byte>> load(const core::plan::ExchangePlan& plan) const;

    /// Saves the image atomically; false (and logged) on failure, the old file kept.
    bool save(const core::plan::ExchangePlan& plan, std::span<const std::byte> data) const;

    /// Removes the exchange's file (exchange removed from the configuration).
    void remove(const core::plan::ExchangePlan& plan) const;

    /// Path of the exchange's file.
    std::string path_of(const core::plan::ExchangePlan& plan) const;

private:
    std::string directory_;
};

}  // namespace eip2mqtt::adapters::state
