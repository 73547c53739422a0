#pragma once
/// A compact, read-only YAML document built from yaml-cpp's event API, for the configuration
/// loader. `YAML::Load` builds a graph of shared, individually allocated nodes, kilobytes of
/// heap per tag of a configuration (docs/decisions/0001-configurations-of-100000-tags.md); this
/// keeps one flat array of
/// nodes, one of children and one of scalar text, with each node's `YAML::Mark` so that
/// diagnostics keep yaml-cpp's line and column. yaml-cpp still does all the parsing.
///
/// Module-private to src/adapters/yaml.

#include <yaml-cpp/mark.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::adapters::yaml::detail {

class Tree;

/// A node of a Tree, or an undefined node (a key that is not in its mapping). A cheap handle:
/// copy it freely while its Tree lives.
class Node {
public:
    Node() = default;

    bool is_defined() const { return tree_ != nullptr; }
    /// `~`, `null`, an empty value; false when undefined.
    bool is_null() const;
    bool is_scalar() const;
    bool is_sequence() const;
    bool is_map() const;

    /// The scalar's text as written (after YAML unquoting); empty for any other node.
    std::string_view scalar() const;
    /// Where the node starts, as yaml-cpp reports it (0-based); null_mark() when undefined.
    YAML::Mark mark() const;

    /// Items of a sequence or entries of a mapping; 0 for other nodes.
    std::size_t size() const;
    /// Item `i` of a sequence (i < size()).
    Node item(std::size_t i) const;
    /// Key and value of entry `i` of a mapping (i < size()), in document order; duplicate keys
    /// are kept, as yaml-cpp keeps them, so that the loader can report them.
    Node key(std::size_t i) const;
    Node value(std::size_t i) const;
    /// The value of the first entry whose key is the scalar `key`; undefined when none (or when
    /// this is not a mapping), as `YAML::Node::operator[]` on a const node.
    Node find(std::string_view key) const;

private:
    friend class Tree;
    Node(const Tree* tree, std::uint32_t index) : tree_(tree), index_(index) {}

    const Tree* tree_ = nullptr;
    std::uint32_t index_ = 0;
};

/// A parsed YAML document (the first one of the text, as `YAML::Load` reads).
class Tree {
public:
    /// Thrown by parse() once its `stop` is requested.
    struct Cancelled {};

    /// Parses `text`; throws YAML::Exception (with its mark) on a syntax error, as YAML::Load,
    /// and Cancelled soon after `stop` is requested (every thousand nodes or so).
    static Tree parse(const std::string& text, std::stop_token stop = {});

    /// The document's root; undefined when the text holds no document (empty or comments only).
    Node root() const;

private:
    friend class Node;
    friend class Builder;
    struct Parsed;

    enum class Kind : std::uint8_t { null, scalar, sequence, map };

    struct Entry {
        std::uint32_t first = 0;  ///< scalar: offset in text_; sequence, map: offset in children_
        std::uint32_t count = 0;  ///< scalar: length; sequence: items; map: 2 x entries
        std::int32_t line = 0;    ///< yaml-cpp's 0-based line, -1 for a null mark
        std::int32_t column = 0;  ///< yaml-cpp's 0-based column
        Kind kind = Kind::null;
    };

    /// Keeps the arrays below alive, at fixed addresses: a parse's vectors.
    std::shared_ptr<const void> storage_;
    std::span<const Entry> nodes_;
    std::span<const std::uint32_t> children_;  ///< items, or key and value of each entry
    std::string_view text_;                    ///< every scalar's text, end to end
    std::uint32_t root_ = 0;
    bool has_root_ = false;
};

}  // namespace eip2mqtt::adapters::yaml::detail
