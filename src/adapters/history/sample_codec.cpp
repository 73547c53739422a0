#include "eip2mqtt/adapters/history/sample_codec.hpp"

#include <bit>
#include <cstring>
#include <type_traits>

namespace eip2mqtt::adapters::history {
namespace {

enum Kind : std::uint8_t { bool_false, bool_true, int64, uint64, float32, float64, text, list };

// A string tag's UTF-8 text is at most two bytes per byte of an exchange; an array has at most
// one element per byte. Larger counts are not ours, whatever the bytes say.
constexpr std::uint64_t max_text_bytes = 2 * 1400;
constexpr std::uint64_t max_list_items = 1400 * 8;

void put_varint(std::uint64_t v, std::string& out) {
    while (v >= 0x80) {
        out.push_back(static_cast<char>((v & 0x7F) | 0x80));
        v >>= 7;
    }
    out.push_back(static_cast<char>(v));
}

template <class T>
void put_fixed(T v, std::string& out) {
    auto bits = std::bit_cast<std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>(v);
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        out.push_back(static_cast<char>(bits & 0xFF));
        bits >>= 8;
    }
}

class Reader {
public:
    explicit Reader(std::string_view bytes) : bytes_(bytes) {}
    bool done() const { return at_ == bytes_.size(); }

    bool varint(std::uint64_t& v) {
        v = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            if (at_ == bytes_.size()) return false;
            const auto byte = static_cast<std::uint8_t>(bytes_[at_++]);
            v |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
            if ((byte & 0x80) == 0) return shift < 63 || byte <= 1;
        }
        return false;
    }
    bool byte(std::uint8_t& b) {
        if (at_ == bytes_.size()) return false;
        b = static_cast<std::uint8_t>(bytes_[at_++]);
        return true;
    }
    bool text(std::string& v) {
        std::uint64_t size = 0;
        if (!varint(size) || size > max_text_bytes || bytes_.size() - at_ < size) return false;
        v.assign(bytes_.substr(at_, size));
        at_ += size;
        return true;
    }
    template <class T>
    bool fixed(T& v) {
        if (bytes_.size() - at_ < sizeof(T)) return false;
        std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t> bits = 0;
        for (std::size_t i = 0; i < sizeof(T); ++i) {
            bits |= static_cast<decltype(bits)>(static_cast<std::uint8_t>(bytes_[at_ + i]))
                    << (8 * i);
        }
        at_ += sizeof(T);
        v = std::bit_cast<T>(bits);
        return true;
    }

private:
    std::string_view bytes_;
    std::size_t at_ = 0;
};

void put_value(const core::plan::Value& value, std::string& out) {
    std::visit(
        [&out](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, bool>) {
                out.push_back(static_cast<char>(v ? bool_true : bool_false));
            } else if constexpr (std::is_same_v<T, std::int64_t>) {
                out.push_back(static_cast<char>(int64));
                // Zigzag: small negative numbers stay short.
                put_varint(
                    (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63),
                    out);
            } else if constexpr (std::is_same_v<T, std::uint64_t>) {
                out.push_back(static_cast<char>(uint64));
                put_varint(v, out);
            } else if constexpr (std::is_same_v<T, float>) {
                out.push_back(static_cast<char>(float32));
                put_fixed(v, out);
            } else if constexpr (std::is_same_v<T, double>) {
                out.push_back(static_cast<char>(float64));
                put_fixed(v, out);
            } else if constexpr (std::is_same_v<T, core::plan::Text>) {
                out.push_back(static_cast<char>(text));
                put_varint(v->size(), out);
                out += *v;
            } else {
                out.push_back(static_cast<char>(list));
                put_varint(v->items.size(), out);
                for (const auto& item : v->items) put_value(item, out);
            }
        },
        value);
}

}  // namespace

void encode_samples(std::span<const JournaledSample> samples, std::string& out) {
    for (const auto& sample : samples) {
        put_varint(sample.tag, out);
        put_value(sample.value, out);
    }
}

namespace {

/// A value of `kind`; an error text for bytes that are not one. An array's elements are
/// scalars: `in_list` refuses a list or a text within one.
core::Result<core::plan::Value, std::string> read_value(Reader& in, std::uint8_t kind,
                                                        bool in_list = false) {
    std::uint64_t u = 0;
    float f = 0;
    double d = 0;
    switch (kind) {
        case bool_false:
        case bool_true:
            return core::plan::Value{kind == bool_true};
        case int64:
            if (!in.varint(u)) return core::fail(std::string("a truncated integer"));
            return core::plan::Value{static_cast<std::int64_t>((u >> 1) ^ (~(u & 1) + 1))};
        case uint64:
            if (!in.varint(u)) return core::fail(std::string("a truncated integer"));
            return core::plan::Value{u};
        case float32:
            if (!in.fixed(f)) return core::fail(std::string("a truncated float"));
            return core::plan::Value{f};
        case float64:
            if (!in.fixed(d)) return core::fail(std::string("a truncated double"));
            return core::plan::Value{d};
        case text: {
            std::string t;
            if (in_list || !in.text(t)) return core::fail(std::string("a bad text"));
            return core::plan::make_text(std::move(t));
        }
        case list:
            break;
        default:
            return core::fail("an unknown value kind " + std::to_string(kind));
    }
    if (in_list || !in.varint(u) || u > max_list_items) {
        return core::fail(std::string("a bad array"));
    }
    std::vector<core::plan::Value> items;
    for (std::uint64_t i = 0; i < u; ++i) {
        std::uint8_t item_kind = 0;
        if (!in.byte(item_kind)) return core::fail(std::string("a truncated array"));
        auto item = read_value(in, item_kind, true);
        if (!item) return item;
        items.push_back(std::move(item).value());
    }
    return core::plan::make_list(std::move(items));
}

}  // namespace

core::Result<std::vector<JournaledSample>, std::string> decode_samples(std::string_view bytes) {
    std::vector<JournaledSample> samples;
    Reader in(bytes);
    while (!in.done()) {
        std::uint64_t tag = 0;
        std::uint8_t kind = 0;
        if (!in.varint(tag) || tag > UINT32_MAX || !in.byte(kind)) {
            return core::fail(std::string("a truncated or bad tag index"));
        }
        auto value = read_value(in, kind);
        if (!value) return core::fail(value.error());
        samples.push_back({static_cast<std::uint32_t>(tag), std::move(value).value()});
    }
    return samples;
}

}  // namespace eip2mqtt::adapters::history
