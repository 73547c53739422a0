#pragma once
/// Persisted produced images (issue #3): one file per produced exchange in `state_dir`
/// (ImageFile), so a restart keeps producing the last written values rather than zeros. A file
/// carries a layout fingerprint: a file written for another layout (length, tag addresses or
/// types) is ignored, so `initial` values apply instead.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/state/image_file.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::adapters::state {

/// A fingerprint of what the bytes of an image mean: length, and each tag's address and type.
std::uint64_t layout_fingerprint(const core::plan::ExchangePlan& plan);

class ImageStore {
public:
    /// Nothing is read or written until asked; the gateway made `directory` (StateDirLock).
    explicit ImageStore(std::string directory);

    /// The exchange's file, read now (ImageFile).
    std::shared_ptr<ImageFile> open(const core::plan::ExchangePlan& plan) const;

    /// The image saved for this exchange, read now: nullopt when missing, unreadable, corrupt
    /// or of another layout (logged once at info or warn).
    std::optional<std::vector<std::byte>> load(const core::plan::ExchangePlan& plan) const;

    /// Path of the exchange's file.
    std::string path_of(const core::plan::ExchangePlan& plan) const;

private:
    std::string directory_;
};

}  // namespace eip2mqtt::adapters::state
