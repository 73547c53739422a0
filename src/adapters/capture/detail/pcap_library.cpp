#include "adapters/capture/detail/pcap_library.hpp"

#include <dlfcn.h>

#include <string>

#include "eip2mqtt/adapters/capture/packet_capture.hpp"

namespace eip2mqtt::adapters::capture::detail {
namespace {

[[noreturn]] void fail(const std::string& what) {
    const char* reason = ::dlerror();
    throw CaptureError(what + (reason != nullptr ? std::string(": ") + reason : std::string()),
                       false);
}

template <typename Function>
void resolve(void* library, const char* name, Function& function) {
    function = reinterpret_cast<Function>(::dlsym(library, name));
    if (function == nullptr) fail(std::string("libpcap lacks ") + name);
}

PcapLibrary load() {
    void* library = ::dlopen(pcap_soname(), RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
        fail(std::string("cannot capture without libpcap (") + pcap_soname() + ")");
    }
    PcapLibrary pcap{};
    resolve(library, "pcap_create", pcap.create);
    resolve(library, "pcap_set_snaplen", pcap.set_snaplen);
    resolve(library, "pcap_set_immediate_mode", pcap.set_immediate_mode);
    resolve(library, "pcap_set_buffer_size", pcap.set_buffer_size);
    resolve(library, "pcap_activate", pcap.activate);
    resolve(library, "pcap_statustostr", pcap.statustostr);
    resolve(library, "pcap_compile", pcap.compile);
    resolve(library, "pcap_setfilter", pcap.setfilter);
    resolve(library, "pcap_freecode", pcap.freecode);
    resolve(library, "pcap_setnonblock", pcap.setnonblock);
    resolve(library, "pcap_get_selectable_fd", pcap.get_selectable_fd);
    resolve(library, "pcap_datalink", pcap.datalink);
    resolve(library, "pcap_dispatch", pcap.dispatch);
    resolve(library, "pcap_stats", pcap.stats);
    resolve(library, "pcap_geterr", pcap.geterr);
    resolve(library, "pcap_close", pcap.close);
    return pcap;  // the library stays loaded: its functions are used until exit
}

}  // namespace

const char* pcap_soname() { return EIP2MQTT_PCAP_SONAME; }

const PcapLibrary& pcap_library() {
    static const PcapLibrary pcap = load();  // a failed load throws and is tried again next time
    return pcap;
}

}  // namespace eip2mqtt::adapters::capture::detail
