#pragma once
/// Captures the datagrams sent to one UDP socket (bound by the test, in a namespace of its own
/// say) with the kernel's time of arrival (SO_TIMESTAMPNS), so a loaded machine's scheduling of
/// the capture's thread never moves two datagrams closer together than they came. A thread of
/// its own, from the constructor to stop() or the destructor.

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace eip2mqtt::test {

class SegmentCapture {
public:
    struct Datagram {
        std::string source;               ///< dotted IPv4 address of the sender
        std::chrono::milliseconds at{0};  ///< arrival, since `epoch` (the system clock's)
        std::vector<std::byte> bytes;
    };
    /// Reads `fd` (bound; taken, closed at the end).
    SegmentCapture(int fd, std::chrono::system_clock::time_point epoch);
    ~SegmentCapture();
    SegmentCapture(const SegmentCapture&) = delete;
    SegmentCapture& operator=(const SegmentCapture&) = delete;

    void stop();
    std::vector<Datagram> datagrams() const;

private:
    void run();

    int fd_;
    std::chrono::system_clock::time_point epoch_;
    mutable std::mutex mutex_;
    std::vector<Datagram> datagrams_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace eip2mqtt::test
