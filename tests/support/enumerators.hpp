#pragma once
/// Which numbers of an enum are its enumerators, read from the compiler's own spelling of a
/// template argument: GCC and Clang write a named value as `V = ns::Enum::name` and any other as
/// `V = (ns::Enum)3`. For the tests that an enum's name table (core/enum_names.hpp) names every
/// value it has, and nothing else.

#include <gtest/gtest.h>

#include <cstddef>
#include <set>
#include <string_view>
#include <utility>

#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::test {

template <auto V>
constexpr bool is_enumerator() {
    constexpr std::string_view signature = __PRETTY_FUNCTION__;
    constexpr std::string_view lead = "V = ";
    constexpr auto at = signature.find(lead);
    static_assert(at != std::string_view::npos, "an unknown spelling of __PRETTY_FUNCTION__");
    return signature[at + lead.size()] != '(';
}

/// How far the search for enumerators reaches: past the end of every enum it checks.
inline constexpr std::size_t enumerator_search_limit = 64;

/// Whether the enumerators of `Enum` are exactly the numbers 0 to `count` - 1 (below the
/// search limit).
template <class Enum, std::size_t count>
constexpr bool enumerators_are_first() {
    return []<std::size_t... i>(std::index_sequence<i...>) {
        return ((is_enumerator<static_cast<Enum>(i)>() == (i < count)) && ...);
    }
    (std::make_index_sequence<enumerator_search_limit>());
}

/// Every value of `Enum` has a name and every name a value; the names are distinct, not empty,
/// and each parses back to its value.
template <class Enum, std::size_t N>
void expect_every_value_named(const core::EnumNames<Enum, N>& names) {
    EXPECT_TRUE((enumerators_are_first<Enum, N>()))
        << "the enum has another number of values than the " << N << " names";
    std::set<std::string_view> seen;
    for (const auto value : names.values()) {
        const auto name = names.name_of(value);
        EXPECT_FALSE(name.empty());
        EXPECT_TRUE(seen.insert(name).second) << "the name " << name << " is given twice";
        EXPECT_EQ(names.parse(name), value) << name;
    }
}

}  // namespace eip2mqtt::test
