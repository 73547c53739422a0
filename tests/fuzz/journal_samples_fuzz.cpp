// Fuzzes the reading of a journal entry's samples, which come from a file on disk that a power
// loss, a full disk or a person may have damaged: any bytes must give an error or samples, and
// samples must encode back to the bytes they came from.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "eip2mqtt/adapters/history/sample_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const auto samples = eip2mqtt::adapters::history::decode_samples(bytes);
    if (!samples) return 0;
    std::string again;
    eip2mqtt::adapters::history::encode_samples(samples.value(), again);
    // Decoding then encoding may only normalise (a longer LEB128 spelling of the same number);
    // decoding that again must give the same samples.
    const auto twice = eip2mqtt::adapters::history::decode_samples(again);
    if (!twice || twice.value().size() != samples.value().size()) __builtin_trap();
    return 0;
}
