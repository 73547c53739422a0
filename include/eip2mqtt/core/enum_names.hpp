#pragma once
/// EnumNames: the names of an enum's values in one array, declared beside the enum, from which
/// its `to_string`, its parsing and the list of its values all read. The enum's values count
/// from 0 without gaps, in the order of the names (tests/core/enum_names_test.cpp checks, for
/// every such enum, that each value has a name and each name a value).
///
/// Threading: immutable constants; any thread.

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace eip2mqtt::core {

template <class Enum, std::size_t N>
class EnumNames {
public:
    explicit constexpr EnumNames(const std::array<std::string_view, N>& names) : names_(names) {}

    static constexpr std::size_t size() { return N; }

    /// The value's name; "unknown" for a number that names no value (a cast, a bad read).
    constexpr std::string_view name_of(Enum value) const {
        const auto index = static_cast<std::size_t>(value);
        return index < N ? names_[index] : std::string_view("unknown");
    }

    /// The value named exactly `name`; nullopt when none is.
    constexpr std::optional<Enum> parse(std::string_view name) const {
        for (std::size_t i = 0; i < N; ++i) {
            if (names_[i] == name) return static_cast<Enum>(i);
        }
        return std::nullopt;
    }

    /// Every value, in order.
    constexpr std::array<Enum, N> values() const {
        std::array<Enum, N> out{};
        for (std::size_t i = 0; i < N; ++i) out[i] = static_cast<Enum>(i);
        return out;
    }

    constexpr const std::array<std::string_view, N>& names() const { return names_; }

private:
    std::array<std::string_view, N> names_;
};

/// The names of `Enum`'s values, in the order of its enumerators:
/// `inline constexpr auto quality_names = enum_names<Quality>("good", "stale", "bad");`
template <class Enum, class... Names>
constexpr EnumNames<Enum, sizeof...(Names)> enum_names(const Names&... names) {
    return EnumNames<Enum, sizeof...(Names)>({std::string_view(names)...});
}

}  // namespace eip2mqtt::core
