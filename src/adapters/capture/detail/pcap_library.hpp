#pragma once
/// libpcap, loaded when a capture is first opened (dlopen) rather than with the binary.
///
/// Only `sniff` captures. Linked at start, libpcap and the libdbus it needs would be mapped,
/// relocated and partly resident in every process, `run` included, for nothing: about 0.2 MB
/// of a gateway's resident memory. Loaded here, they cost that only where a capture is made.
///
/// Threading: pcap_library() may be called from any thread; the table it returns is immutable.

#include <pcap/pcap.h>

namespace eip2mqtt::adapters::capture::detail {

/// The libpcap functions PacketCapture calls, each resolved from the loaded library.
struct PcapLibrary {
    decltype(&::pcap_create) create;
    decltype(&::pcap_set_snaplen) set_snaplen;
    decltype(&::pcap_set_immediate_mode) set_immediate_mode;
    decltype(&::pcap_set_buffer_size) set_buffer_size;
    decltype(&::pcap_activate) activate;
    decltype(&::pcap_statustostr) statustostr;
    decltype(&::pcap_compile) compile;
    decltype(&::pcap_setfilter) setfilter;
    decltype(&::pcap_freecode) freecode;
    decltype(&::pcap_setnonblock) setnonblock;
    decltype(&::pcap_get_selectable_fd) get_selectable_fd;
    decltype(&::pcap_datalink) datalink;
    decltype(&::pcap_dispatch) dispatch;
    decltype(&::pcap_stats) stats;
    decltype(&::pcap_geterr) geterr;
    decltype(&::pcap_close) close;
};

/// The library named `soname`, loaded on the first call and kept for the process's life.
/// Throws CaptureError naming the library when it cannot be loaded or lacks a function.
const PcapLibrary& pcap_library();

/// The soname pcap_library() loads (the one the build found, e.g. `libpcap.so.0.8`).
const char* pcap_soname();

}  // namespace eip2mqtt::adapters::capture::detail
