// Fuzzes string and array tags: any bytes read as a string field (trimmed or not) and as an
// array of each type, written back, and any text offered as a write. A field read with its
// padding and written back must give the same bytes, so must an array, Latin-1 text must
// round-trip, and text the gateway accepts must fit the field.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/latin1.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace {

using namespace eip2mqtt::core;

plan::TagSpec field(plan::TagType type, std::size_t count) {
    plan::TagSpec tag;
    tag.name = "T";
    tag.type = type;
    tag.count = static_cast<std::uint16_t>(count);
    tag.writable = true;
    return tag;
}

void check_string(std::span<const std::byte> bytes) {
    auto tag = field(plan::TagType::string, bytes.size());
    const auto kept = plan::decode_tag(bytes, tag, plan::Padding::keep);
    std::vector<std::byte> written(bytes.size());
    plan::encode_tag(written, tag, kept);
    if (!std::equal(written.begin(), written.end(), bytes.begin())) std::abort();
    const auto published = plan::decode_tag(bytes, tag);
    (void)plan::to_json(published);
    // What the gateway publishes, written back as a write, fits the field it came from.
    if (!write::validate_write(tag, write::WriteInput{*std::get<plan::Text>(published)})) {
        std::abort();
    }
}

void check_arrays(std::span<const std::byte> bytes, std::uint8_t selector) {
    constexpr plan::TagType types[] = {
        plan::TagType::bit,  plan::TagType::byte, plan::TagType::int_,
        plan::TagType::word, plan::TagType::dint, plan::TagType::udint,
        plan::TagType::real, plan::TagType::lint, plan::TagType::lreal};
    const auto type = types[selector % 9];
    const std::size_t count =
        type == plan::TagType::bit ? bytes.size() * 8 : bytes.size() / plan::size_of(type);
    if (count < 2 || count > 65535) return;
    const auto tag = field(type, count);
    const auto value = plan::decode_tag(bytes, tag);
    std::vector<std::byte> written(bytes.size());
    plan::encode_tag(written, tag, value);
    // Every byte the array covers comes back, a signalling NaN's too.
    if (!std::equal(written.begin(),
                    written.begin() + static_cast<std::ptrdiff_t>(plan::tag_size(tag)),
                    bytes.begin())) {
        std::abort();
    }
    (void)plan::to_json(value);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1 || size > 1401) return 0;
    const auto bytes = std::as_bytes(std::span(data + 1, size - 1));
    if (!bytes.empty()) {
        check_string(bytes);
        check_arrays(bytes, data[0]);
    }
    // Any text as a write: what is accepted has a Latin-1 form no longer than the field.
    const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
    const auto latin1 = plan::utf8_to_latin1(text);
    if (latin1 && plan::latin1_to_utf8(std::as_bytes(std::span(latin1->data(), latin1->size())),
                                       false) != text) {
        std::abort();
    }
    const auto tag = field(plan::TagType::string, data[0] % 16 + 1);
    const auto accepted = write::validate_write(tag, write::WriteInput{text});
    if (accepted && (!latin1 || latin1->size() > tag.count)) std::abort();
    return 0;
}
