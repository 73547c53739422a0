// The Sparkplug bdSeq across restarts: one line of text in the state directory.

#include "eip2mqtt/adapters/state/bd_seq_file.hpp"

#include <spdlog/spdlog.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <span>
#include <sstream>

#include "eip2mqtt/adapters/state/atomic_file.hpp"

namespace eip2mqtt::adapters::state {

std::optional<std::uint8_t> BdSeqFile::read() const {
    std::ifstream in(path_);
    if (!in) {
        if (errno != ENOENT) {
            spdlog::warn("Sparkplug bdSeq file {} cannot be read ({}): bdSeq starts at 0", path_,
                         std::strerror(errno));
        }
        return std::nullopt;
    }
    std::stringstream text;
    text << in.rdbuf();
    const auto content = text.str();
    unsigned value = 0;
    const auto* end = content.data() + content.size();
    const auto [last, error] = std::from_chars(content.data(), end, value);
    const bool rest_is_newline = last == end || (last + 1 == end && *last == '\n');
    if (error != std::errc() || !rest_is_newline || value > 255) {
        spdlog::warn("Sparkplug bdSeq file {} holds no bdSeq (0-255): bdSeq starts at 0", path_);
        return std::nullopt;
    }
    return static_cast<std::uint8_t>(value);
}

void BdSeqFile::write(std::uint8_t bd_seq) {
    const auto text = std::to_string(bd_seq) + "\n";
    const std::array parts{std::as_bytes(std::span(text.data(), text.size()))};
    const auto failure = write_file_atomically(path_, parts, 0644);
    if (!failure) {
        failure_logged_ = false;
        return;
    }
    if (failure_logged_) return;
    failure_logged_ = true;
    spdlog::error(
        "Sparkplug bdSeq {} not kept in {}: {} failed ({}); a restart would start bdSeq again "
        "at 0 (said once until a write succeeds)",
        bd_seq, path_, failure->step, std::strerror(failure->error));
}

}  // namespace eip2mqtt::adapters::state
