#pragma once
/// The bdSeq of a Sparkplug edge node's last will, kept in the state directory so that a
/// restart goes on from it: Sparkplug B 3.0 wants each CONNECT's will one more than the last,
/// across restarts too, or a host holding the old session's NBIRTH could take the new NDEATH
/// for a death of the node it already buried. One line of decimal text, replaced atomically.

#include <cstdint>
#include <optional>
#include <string>

namespace eip2mqtt::adapters::state {

class BdSeqFile {
public:
    /// `path`: the file, in the gateway's state directory.
    explicit BdSeqFile(std::string path) : path_(std::move(path)) {}

    /// The bdSeq written last; nullopt when there is none yet, or the file cannot be read or
    /// holds no bdSeq (logged: the node then starts again at 0).
    std::optional<std::uint8_t> read() const;
    /// Keeps `bd_seq`; a failure is logged once until a write succeeds again, and costs only
    /// the continuity after the next restart.
    void write(std::uint8_t bd_seq);

    const std::string& path() const { return path_; }

private:
    std::string path_;
    bool failure_logged_ = false;
};

}  // namespace eip2mqtt::adapters::state
