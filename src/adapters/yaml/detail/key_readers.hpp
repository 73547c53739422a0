#pragma once
/// How each key of a mapping is read into its field: one table per mapping, beside the reader
/// code that walks it. A table lists the keys of core/config/config_keys.hpp in their order (a
/// table that names another key, or leaves one out, does not compile), so that each key is
/// written once for its reload rule and once with its reading, and the two cannot drift apart.
///
/// Module-private to src/adapters/yaml.

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "adapters/yaml/detail/reader.hpp"
#include "eip2mqtt/core/plan/location.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// One key's value while a table's reader reads it: the Reader's scalar readers, each reporting
/// a value that does not parse at the key's mark, as "<problem> for '<key>'".
class KeyValue {
public:
    KeyValue(Reader& reader, const std::string& key, const Node& value, const Mark& at)
        : reader_(reader), key_(key), value_(value), at_(at) {}

    const std::string& key() const { return key_; }
    const Node& node() const { return value_; }
    const Mark& at() const { return at_; }

    void error(std::string message) { reader_.error(at_, std::move(message)); }

    /// The value as a string (empty for a null value).
    std::optional<std::string> text() { return reader_.text(value_, key_, at_); }
    std::optional<bool> boolean() { return reader_.boolean(value_, key_, at_); }
    std::optional<double> number() { return reader_.number(value_, key_, at_); }
    std::optional<core::plan::TimestampSource> timestamp_source() {
        return reader_.timestamp_source(value_, key_, at_);
    }

    /// An integer within `min`..`max` (as the type `T` reads it: a message names its range).
    template <class T>
    std::optional<T> integer(T min = std::numeric_limits<T>::min(),
                             T max = std::numeric_limits<T>::max()) {
        return reader_.integer<T>(value_, key_, at_, min, max);
    }

    /// A string read by `parse` (returning an optional); reported as "<key> '<text>' <problem>"
    /// when it does not parse.
    template <class Parse>
    auto parsed(Parse parse, std::string_view problem) {
        return reader_.parsed(value_, key_, at_, parse, problem);
    }

    /// The value as a string or a list of strings (`url: a` or `url: [a, b]`), each item read
    /// and reported at its own line and column; `marks` gets each one's (a single string's is
    /// at()). nullopt when the value or an item did not read.
    std::optional<std::vector<std::string>> texts(std::vector<Mark>& marks) {
        if (!value_.is_sequence()) {
            auto s = text();
            if (s) marks.push_back(at_);
            return s ? std::optional(std::vector<std::string>{std::move(*s)}) : std::nullopt;
        }
        std::vector<std::string> out;
        bool read = true;
        for (std::size_t i = 0; i < value_.size(); ++i) {
            const Node item = value_.item(i);
            marks.push_back(reader_.mark(item));
            auto s = reader_.text(item, key_, marks.back());
            read = read && s.has_value();
            out.push_back(s.value_or(std::string()));
        }
        return read ? std::optional(std::move(out)) : std::nullopt;
    }
    /// The value as a list of two numbers (`raw: [0, 32000]`), each reported at its own mark.
    std::optional<std::array<double, 2>> number_pair() {
        if (!value_.is_sequence() || value_.size() != 2) {
            error("expected two numbers for " + in_quotes(key_) + ", as [low, high]");
            return std::nullopt;
        }
        const auto first = reader_.number(value_.item(0), key_, reader_.mark(value_.item(0)));
        const auto second = reader_.number(value_.item(1), key_, reader_.mark(value_.item(1)));
        if (!first || !second) return std::nullopt;
        return std::array<double, 2>{*first, *second};
    }
    /// The value as a `location:` mapping of names to texts (null: none), each name and text
    /// read and reported at its own mark. Whether the names and texts may be topic levels is
    /// the core's to check.
    std::optional<core::plan::Location> location() {
        core::plan::Location out;
        if (value_.is_null()) return out;
        if (!value_.is_map()) {
            error("expected a mapping of names to texts for " + in_quotes(key_) +
                  ", as { area: turbine-hall }");
            return std::nullopt;
        }
        bool read = true;
        for (std::size_t i = 0; i < value_.size(); ++i) {
            const Node name_node = value_.key(i);
            const Node text_node = value_.value(i);
            auto name = reader_.text(name_node, key_, reader_.mark(name_node));
            auto text = reader_.text(text_node, key_, reader_.mark(text_node));
            if (name && out.find(*name)) {
                error_at(reader_.mark(name_node),
                         "location key " + in_quotes(*name) + " is written twice");
                name.reset();
            }
            read = read && name && text;
            if (name && text) out.levels.emplace_back(std::move(*name), std::move(*text));
        }
        return read ? std::optional(std::move(out)) : std::nullopt;
    }
    bool location_to(core::plan::Location& field) { return store(field, location()); }

    /// Reports `message` at `at` (an item's mark, from texts()).
    void error_at(const Mark& at, std::string message) { reader_.error(at, std::move(message)); }

    /// Each of these stores the value in `field` (converted to the field's type: an integer to
    /// a duration) and returns true; false, the field untouched, when it did not read.
    bool text_to(std::string& field) { return store(field, text()); }
    bool boolean_to(bool& field) { return store(field, boolean()); }
    bool number_to(double& field) { return store(field, number()); }
    template <class T, class Field>
    bool integer_to(Field& field, T min = std::numeric_limits<T>::min(),
                    T max = std::numeric_limits<T>::max()) {
        return store(field, integer<T>(min, max));
    }

    /// The value as a mapping whose keys `readers` read into `into`, named `where` in messages
    /// ("unknown key 'x' in mqtt.tls"); the marks of its keys.
    template <class Into, std::size_t N>
    Marks mapping(const std::string& where, const KeyReaders<Into, N>& readers, Into& into) {
        return reader_.read_keys(value_, at_, key_, where, readers, into);
    }

private:
    template <class Field, class T>
    static bool store(Field& field, const std::optional<T>& value) {
        if (value) field = Field(*value);
        return value.has_value();
    }

    Reader& reader_;
    const std::string& key_;
    const Node& value_;
    const Mark& at_;
};

/// One row of a table: a key and how its value is read into `Into` (a section, or an exchange
/// or a tag while it is read). The reader returns false when the value did not read (it was
/// reported); whether that leaves an exchange or a tag out is its walk's to decide.
template <class Into>
struct KeyReader {
    std::string_view name;
    bool (*read)(KeyValue& value, Into& into);
};

/// A table found to list its config_keys.hpp keys in their order (the Reader walks these names).
template <class Into, std::size_t N>
struct KeyReaders {
    std::array<std::string_view, N> names;
    std::array<bool (*)(KeyValue&, Into&), N> read;
};

/// Called only when a table and its config_keys.hpp keys disagree: being no constexpr function,
/// it stops the compilation of the table, which names this function in the error.
void table_keys_differ_from_config_keys();

/// The table `readers`, checked at compile time against the keys `keys` of config_keys.hpp.
template <class Into, class Of, std::size_t N>
consteval KeyReaders<Into, N> bind_keys(const std::array<core::config::ConfigKey<Of>, N>& keys,
                                        const KeyReader<Into> (&readers)[N]) {
    KeyReaders<Into, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        if (readers[i].name != keys[i].name) table_keys_differ_from_config_keys();
        out.names[i] = keys[i].name;
        out.read[i] = readers[i].read;
    }
    return out;
}

template <class Into, std::size_t N, class Where, class Failed>
Marks Reader::read_keys(const Node& node, const Mark& at, const std::string& what,
                        const Where& where, const KeyReaders<Into, N>& readers, Into& into,
                        const Failed& failed) {
    return walk_indexed(
        node, at, what, where, readers.names,
        [&](std::size_t index, const std::string& key, const Node& value, const Mark& k) {
            KeyValue read_value(*this, key, value, k);
            if (!readers.read[index](read_value, into)) failed(key);
        });
}

}  // namespace eip2mqtt::adapters::yaml::detail
