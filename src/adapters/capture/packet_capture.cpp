#include "eip2mqtt/adapters/capture/packet_capture.hpp"

#include <unistd.h>

#include <boost/asio/error.hpp>

#include "adapters/capture/detail/pcap_library.hpp"

namespace eip2mqtt::adapters::capture {
namespace {

// Frames read per wake-up before yielding to the loop's other handlers.
constexpr int max_frames_per_wakeup = 256;

/// libpcap's functions, loaded by the first capture (detail/pcap_library.hpp says why).
const detail::PcapLibrary& lib() { return detail::pcap_library(); }

[[noreturn]] void fail(::pcap* handle, const std::string& what, bool permission = false) {
    std::string message = what;
    if (handle != nullptr) {
        message += ": ";
        message += lib().geterr(handle);
        lib().close(handle);
    }
    throw CaptureError(message, permission);
}

/// pcap_activate's outcome as an exception, the missing privilege told apart.
void check_activation(::pcap* handle, int status, const std::string& interface) {
    if (status >= 0) return;  // warnings (> 0) do not stop a capture
    const std::string where = "cannot capture on '" + interface + "'";
    switch (status) {
        case PCAP_ERROR_PERM_DENIED:
        case PCAP_ERROR_PROMISC_PERM_DENIED:
            fail(handle, where, true);
        case PCAP_ERROR_NO_SUCH_DEVICE:
            fail(handle, where + " (no such interface; `ip link` lists them)");
        default:
            fail(handle, where + " (" + lib().statustostr(status) + ")");
    }
}

}  // namespace

PacketCapture::PacketCapture(boost::asio::any_io_executor executor, const CaptureOptions& options)
    : readable_(executor) {
    char error[PCAP_ERRBUF_SIZE] = {};
    ::pcap* handle = lib().create(options.interface.c_str(), error);
    if (handle == nullptr) throw CaptureError(error, false);
    lib().set_snaplen(handle, options.snapshot_bytes);
    // Each frame as it comes, not a buffer's worth later: sniff prints as datagrams arrive.
    lib().set_immediate_mode(handle, 1);
    lib().set_buffer_size(handle, 4 * 1024 * 1024);
    check_activation(handle, lib().activate(handle), options.interface);

    bpf_program program{};
    if (lib().compile(handle, &program, options.filter.c_str(), 1, PCAP_NETMASK_UNKNOWN) != 0) {
        fail(handle, "capture filter '" + options.filter + "'");
    }
    const int set = lib().setfilter(handle, &program);
    lib().freecode(&program);
    if (set != 0) fail(handle, "capture filter '" + options.filter + "'");
    if (lib().setnonblock(handle, 1, error) != 0) {
        lib().close(handle);
        throw CaptureError(error, false);
    }
    const int fd = lib().get_selectable_fd(handle);
    // Asio closes what it is given: it gets a duplicate, pcap_close closes the original.
    const int duplicate = fd < 0 ? -1 : ::dup(fd);
    if (duplicate < 0) fail(handle, "cannot wait on the capture of '" + options.interface + "'");
    readable_.assign(duplicate);
    handle_ = handle;
    link_type_ = lib().datalink(handle);
}

PacketCapture::~PacketCapture() {
    stop();
    if (handle_ != nullptr) lib().close(handle_);
}

void PacketCapture::start(Handler handler) {
    handler_ = std::move(handler);
    do_wait();
}

void PacketCapture::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    readable_.close(ignored);
}

std::uint64_t PacketCapture::kernel_drops() const {
    pcap_stat counts{};
    return handle_ != nullptr && lib().stats(handle_, &counts) == 0 ? counts.ps_drop : 0;
}

void PacketCapture::do_wait() {
    readable_.async_wait(boost::asio::posix::stream_descriptor::wait_read,
                         [this](const boost::system::error_code& error) { on_readable(error); });
}

void PacketCapture::on_readable(const boost::system::error_code& error) {
    if (error == boost::asio::error::operation_aborted || stopped_) return;
    const auto frame = [](u_char* self, const pcap_pkthdr* header, const u_char* bytes) {
        reinterpret_cast<PacketCapture*>(self)->on_frame(
            {reinterpret_cast<const std::byte*>(bytes), header->caplen});
    };
    lib().dispatch(handle_, max_frames_per_wakeup, frame, reinterpret_cast<u_char*>(this));
    if (!stopped_) do_wait();
}

void PacketCapture::on_frame(std::span<const std::byte> frame) {
    if (stopped_) return;
    ++stats_.frames;
    const auto decoded = decode_frame(link_type_, frame);
    if (!decoded) {
        ++(decoded.error() == FrameSkip::fragment ? stats_.fragments : stats_.skipped);
        return;
    }
    ++stats_.datagrams;
    handler_(decoded.value());
}

}  // namespace eip2mqtt::adapters::capture
