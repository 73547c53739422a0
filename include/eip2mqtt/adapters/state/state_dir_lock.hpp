#pragma once
/// The gateway's hold on its state directory (`gateway.state_dir`), taken at start before
/// anything else opens a file or a socket. The directory is created when missing, locked (an
/// exclusive flock on `eip2mqtt.lock`, which then names its holder), and shown to be writable by
/// creating a file in it. Two gateways sharing one state directory would overwrite each other's
/// images and journal, and a directory the service cannot write would lose every write at the
/// next restart: either way the gateway refuses to start, saying why.
///
/// Threading: constructed and destroyed on the thread that starts the gateway.

#include <string>

namespace eip2mqtt::adapters::state {

/// Who holds the lock, written into the lock file for the next one to read.
struct StateDirOwner {
    std::string gateway_id;
    std::string config_file;
};

class StateDirLock {
public:
    /// The lock file's name inside the state directory.
    static constexpr const char* file_name = "eip2mqtt.lock";

    /// Throws std::runtime_error naming the directory and the reason when it cannot be created
    /// or written, or when another process holds it (then with what its lock file says: pid,
    /// gateway id, configuration file, start time). Warns when the disk holding it is full.
    StateDirLock(const std::string& directory, const StateDirOwner& owner);
    /// Releases the lock. The file stays: removing it would let a third process lock a new file
    /// while a second one still waits on the old.
    ~StateDirLock();
    StateDirLock(const StateDirLock&) = delete;
    StateDirLock& operator=(const StateDirLock&) = delete;

    const std::string& path() const { return path_; }

private:
    std::string path_;
    int fd_ = -1;
};

}  // namespace eip2mqtt::adapters::state
