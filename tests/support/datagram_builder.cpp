#include "tests/support/datagram_builder.hpp"

#include <cctype>
#include <stdexcept>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/encode.hpp"

namespace eip2mqtt::test {

std::vector<std::byte> from_hex(std::string_view hex) {
    std::vector<std::byte> out;
    int high = -1;
    for (const char c : hex) {
        if (std::isspace(static_cast<unsigned char>(c))) continue;
        const int digit = std::isdigit(static_cast<unsigned char>(c))
                              ? c - '0'
                              : std::tolower(static_cast<unsigned char>(c)) - 'a' + 10;
        if (digit < 0 || digit > 15) throw std::invalid_argument("bad hex");
        if (high < 0) {
            high = digit;
        } else {
            out.push_back(static_cast<std::byte>(high << 4 | digit));
            high = -1;
        }
    }
    return out;
}

std::string to_hex(const std::vector<std::byte>& bytes) {
    static constexpr char digits[] = "0123456789abcdef";
    std::string out;
    for (const auto b : bytes) {
        out += digits[std::to_integer<int>(b) >> 4];
        out += digits[std::to_integer<int>(b) & 0xF];
    }
    return out;
}

DatagramBuilder::DatagramBuilder(std::string_view producer_id, std::uint32_t exchange_id,
                                 std::size_t length)
    : data_(length, std::byte{0}) {
    header_.producer_id = core::wire::parse_producer_id(producer_id).value();
    header_.exchange_id = exchange_id;
}

DatagramBuilder& DatagramBuilder::request_id(std::uint16_t rid) {
    header_.request_id = rid;
    return *this;
}

DatagramBuilder& DatagramBuilder::timestamp(std::uint32_t seconds, std::uint32_t nanoseconds) {
    header_.time_s = seconds;
    header_.time_ns = nanoseconds;
    return *this;
}

DatagramBuilder& DatagramBuilder::signature(std::uint8_t major, std::uint8_t minor) {
    header_.signature = core::wire::Signature{major, minor}.to_wire();
    return *this;
}

DatagramBuilder& DatagramBuilder::set(std::string_view address, core::plan::TagType type,
                                      const core::plan::Value& value) {
    core::plan::encode_value(data_, type, core::plan::parse_address(address).value(), value);
    return *this;
}

std::vector<std::byte> DatagramBuilder::build() const {
    std::vector<std::byte> out(core::wire::header_size + data_.size());
    core::wire::encode_header(header_, out);
    std::copy(data_.begin(), data_.end(), out.begin() + core::wire::header_size);
    return out;
}

}  // namespace eip2mqtt::test
