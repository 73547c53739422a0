#pragma once
/// A passive capture of UDP datagrams with libpcap: the kernel hands it a copy of each frame
/// that passes its filter, while the datagram still goes to the socket it was sent to. So a
/// capture can watch a port beside the program that owns it, and never takes anything from it.
/// Capturing needs CAP_NET_RAW (root, or a binary given the capability with setcap).
///
/// Threading: constructed, started and stopped on one loop; the handler runs there.

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "eip2mqtt/adapters/capture/frame.hpp"

struct pcap;

namespace eip2mqtt::adapters::capture {

struct CaptureOptions {
    std::string interface = "any";  ///< a device name; "any": every interface (Linux)
    std::string filter;             ///< a pcap-filter(7) expression, compiled into the kernel
    int snapshot_bytes = 4096;      ///< bytes kept per frame: an EIP datagram with all headers
};

/// Why a capture could not start.
class CaptureError : public std::runtime_error {
public:
    CaptureError(const std::string& message, bool permission_denied)
        : std::runtime_error(message), permission_denied_(permission_denied) {}
    /// The process lacks the privilege to capture (CAP_NET_RAW).
    bool permission_denied() const { return permission_denied_; }

private:
    bool permission_denied_;
};

struct CaptureStats {
    std::uint64_t frames = 0;     ///< frames the filter passed
    std::uint64_t datagrams = 0;  ///< handed on
    std::uint64_t fragments = 0;  ///< IP fragments, not decoded
    std::uint64_t skipped = 0;    ///< frames without an IPv4 UDP datagram (another reason)
};

class PacketCapture {
public:
    using Handler = std::function<void(const UdpFrame& frame)>;

    /// Opens `options.interface` and sets the filter; throws CaptureError on failure.
    PacketCapture(boost::asio::any_io_executor executor, const CaptureOptions& options);
    ~PacketCapture();
    PacketCapture(const PacketCapture&) = delete;
    PacketCapture& operator=(const PacketCapture&) = delete;

    /// Hands each captured UDP datagram to `handler`, its payload valid during the call only.
    void start(Handler handler);
    /// Stops waiting; frames not yet read are not handed on.
    void stop();

    const CaptureStats& stats() const { return stats_; }
    /// Frames the kernel dropped because the capture did not read fast enough.
    std::uint64_t kernel_drops() const;

private:
    void do_wait();
    void on_readable(const boost::system::error_code& error);
    void on_frame(std::span<const std::byte> frame);

    ::pcap* handle_ = nullptr;
    int link_type_ = 0;
    boost::asio::posix::stream_descriptor readable_;  ///< a duplicate of pcap's descriptor
    Handler handler_;
    CaptureStats stats_;
    bool stopped_ = false;
};

}  // namespace eip2mqtt::adapters::capture
