#pragma once
/// A NOTIFY_SOCKET of the test's own: a unix datagram socket that records what a daemon sends
/// with sd_notify, as systemd would receive it.

#include <chrono>
#include <optional>
#include <string>

namespace eip2mqtt::test {

class NotifySocket {
public:
    /// Binds a socket at `path`.
    explicit NotifySocket(std::string path);
    ~NotifySocket();
    NotifySocket(const NotifySocket&) = delete;
    NotifySocket& operator=(const NotifySocket&) = delete;

    const std::string& path() const { return path_; }
    /// The next notification (e.g. "READY=1\nSTATUS=..."), or nullopt after `timeout`.
    std::optional<std::string> receive(std::chrono::milliseconds timeout);
    /// Waits for a notification containing `text`; every notification read on the way is
    /// dropped. The time it arrived, or nullopt after `timeout`.
    std::optional<std::chrono::steady_clock::time_point> wait_for(
        const std::string& text, std::chrono::milliseconds timeout);

private:
    std::string path_;
    int fd_ = -1;
};

}  // namespace eip2mqtt::test
