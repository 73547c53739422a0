#include "eip2mqtt/adapters/state/state_dir_lock.hpp"

#include <fcntl.h>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace eip2mqtt::adapters::state {
namespace {

namespace fs = std::filesystem;

// Below this much room a new image file (8 KiB) or the journal cannot be written for long.
constexpr unsigned long long low_space_bytes = 64 * 1024;

[[noreturn]] void refuse(const std::string& directory, const std::string& why) {
    throw std::runtime_error("gateway.state_dir " + directory + " " + why);
}

std::string errno_text(int error) { return std::strerror(error); }

void make_directory(const std::string& directory) {
    std::error_code error;
    if (fs::is_directory(directory, error)) return;
    if (fs::exists(fs::symlink_status(directory, error))) refuse(directory, "is not a directory");
    fs::create_directories(directory, error);
    if (error) refuse(directory, "cannot be created: " + error.message());
}

/// The holder's lines ("pid 4242", "gateway_id gw"...) as one clause of the refusal.
std::string describe_holder(int fd) {
    std::array<char, 4096> buffer{};
    const auto n = ::pread(fd, buffer.data(), buffer.size() - 1, 0);
    std::istringstream lines(std::string(buffer.data(), n > 0 ? static_cast<std::size_t>(n) : 0));
    std::string line;
    std::string holder;
    while (std::getline(lines, line)) {
        const auto space = line.find(' ');
        if (space == std::string::npos) continue;
        const auto key = line.substr(0, space);
        const auto value = line.substr(space + 1);
        const char* label = key == "pid"          ? "pid "
                            : key == "gateway_id" ? "gateway.id "
                            : key == "config"     ? "config "
                            : key == "started"    ? "started "
                                                  : nullptr;
        if (label == nullptr) continue;
        if (!holder.empty()) holder += ", ";
        holder += label;
        holder += value;
    }
    return holder.empty() ? "it has not written its details yet" : holder;
}

void write_owner(int fd, const StateDirOwner& owner) {
    const auto text =
        fmt::format("pid {}\ngateway_id {}\nconfig {}\nstarted {:%Y-%m-%dT%H:%M:%SZ}\n", ::getpid(),
                    owner.gateway_id, owner.config_file, fmt::gmtime(std::time(nullptr)));
    // Only what a second instance reads to name this one: the lock itself holds without it,
    // so a full disk that refuses these bytes does not stop the start.
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) < 0) {
        spdlog::warn("cannot write {} bytes to the state directory's lock file: {}", text.size(),
                     errno_text(errno));
    }
}

/// Creating a file is what every image and the journal need: checked now, not at the first
/// write a client makes.
void check_writable(const std::string& directory) {
    const auto probe =
        (fs::path(directory) / (".write-test." + std::to_string(::getpid()))).string();
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        refuse(directory, "is not writable: cannot create a file in it (" + errno_text(errno) +
                              "); it must belong to the user the gateway runs as "
                              "(systemd: StateDirectory=)");
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

void warn_when_full(const std::string& directory) {
    struct statvfs fs_info {};
    if (::statvfs(directory.c_str(), &fs_info) != 0) return;
    const auto room = static_cast<unsigned long long>(fs_info.f_bavail) * fs_info.f_frsize;
    if (room >= low_space_bytes) return;
    spdlog::warn(
        "gateway.state_dir {} has {} bytes free: saved images are overwritten in place, but a "
        "new one cannot be created (writes to its exchange are refused until there is room)",
        directory, room);
}

}  // namespace

StateDirLock::StateDirLock(const std::string& directory, const StateDirOwner& owner)
    : path_((fs::path(directory) / file_name).string()) {
    make_directory(directory);
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) {
        refuse(directory, "is not writable: cannot open " + path_ + " (" + errno_text(errno) +
                              "); it must belong to the user the gateway runs as "
                              "(systemd: StateDirectory=)");
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        const auto holder = error == EWOULDBLOCK ? describe_holder(fd_) : std::string();
        ::close(fd_);
        if (error != EWOULDBLOCK) refuse(directory, "cannot be locked: " + errno_text(error));
        refuse(directory, "is in use by another eip2mqtt (" + holder +
                              "): each gateway needs a state_dir of its own; stop the other "
                              "one first");
    }
    try {
        check_writable(directory);
    } catch (...) {
        ::close(fd_);
        throw;
    }
    write_owner(fd_, owner);
    warn_when_full(directory);
}

StateDirLock::~StateDirLock() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace eip2mqtt::adapters::state
