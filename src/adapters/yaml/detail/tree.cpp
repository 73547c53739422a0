#include "adapters/yaml/detail/tree.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <utility>

namespace eip2mqtt::adapters::yaml::detail {

/// What a parse builds, owned by the Tree that views it.
struct Tree::Parsed {
    std::vector<Entry> nodes;
    std::vector<std::uint32_t> children;
    std::string text;
    std::uint32_t root = 0;
    bool has_root = false;
};

/// Turns yaml-cpp's events into a Tree, as YAML::NodeBuilder turns them into YAML::Nodes:
/// a container's children are collected while it is open, then stored next to each other.
class Builder : public YAML::EventHandler {
public:
    Builder(Tree::Parsed& tree, std::stop_token stop) : tree_(tree), stop_(std::move(stop)) {}

    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}

    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        add(Tree::Kind::null, mark, anchor);
    }

    void OnAlias(const YAML::Mark&, YAML::anchor_t anchor) override {
        // yaml-cpp resolves the anchor before this call (an unknown one is a ParserException),
        // and an alias is the anchored node itself, with that node's mark, as in YAML::Node.
        attach(anchors_[anchor]);
    }

    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  const std::string& value) override {
        const auto index = add(Tree::Kind::scalar, mark, anchor);
        auto& node = tree_.nodes[index];
        node.first = static_cast<std::uint32_t>(tree_.text.size());
        node.count = static_cast<std::uint32_t>(value.size());
        tree_.text += value;
    }

    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        open(add(Tree::Kind::sequence, mark, anchor));
    }
    void OnSequenceEnd() override { close(); }

    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                    YAML::EmitterStyle::value) override {
        open(add(Tree::Kind::map, mark, anchor));
    }
    void OnMapEnd() override { close(); }

private:
    struct Open {
        std::uint32_t node;
        std::size_t first_pending;  ///< where its children start in pending_
    };

    std::uint32_t add(Tree::Kind kind, const YAML::Mark& mark, YAML::anchor_t anchor) {
        const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
        // A reload of a gateway that stops gives up here: the parse is most of a load's time.
        if (index % 1024 == 0 && stop_.stop_requested()) throw Tree::Cancelled{};
        Tree::Entry entry;
        entry.kind = kind;
        entry.line = mark.is_null() ? -1 : mark.line;
        entry.column = mark.is_null() ? -1 : mark.column;
        tree_.nodes.push_back(entry);
        if (anchor != YAML::NullAnchor) {
            if (anchors_.size() <= anchor) anchors_.resize(anchor + 1);
            anchors_[anchor] = index;
        }
        attach(index);
        return index;
    }

    void attach(std::uint32_t index) {
        if (open_.empty()) {
            if (!tree_.has_root) {
                tree_.has_root = true;
                tree_.root = index;
            }
            return;
        }
        pending_.push_back(index);
    }

    void open(std::uint32_t index) { open_.push_back({index, pending_.size()}); }

    void close() {
        const Open done = open_.back();
        open_.pop_back();
        auto& node = tree_.nodes[done.node];
        node.first = static_cast<std::uint32_t>(tree_.children.size());
        node.count = static_cast<std::uint32_t>(pending_.size() - done.first_pending);
        tree_.children.insert(tree_.children.end(),
                              pending_.begin() + static_cast<std::ptrdiff_t>(done.first_pending),
                              pending_.end());
        pending_.resize(done.first_pending);
    }

    Tree::Parsed& tree_;
    std::stop_token stop_;
    std::vector<Open> open_;
    std::vector<std::uint32_t> pending_;  ///< children of the open containers, innermost last
    std::vector<std::uint32_t> anchors_;  ///< node of each anchor_t (1-based)
};

Tree Tree::parse(const std::string& text, std::stop_token stop) {
    auto parsed = std::make_shared<Parsed>();
    // Rough sizes for a configuration (a node per ~8 bytes of text) spare most regrowth copies.
    parsed->nodes.reserve(text.size() / 8);
    parsed->children.reserve(text.size() / 8);
    parsed->text.reserve(text.size() / 4);
    std::istringstream in(text);
    YAML::Parser parser(in);
    Builder builder(*parsed, std::move(stop));
    parser.HandleNextDocument(builder);
    parsed->nodes.shrink_to_fit();
    parsed->children.shrink_to_fit();
    parsed->text.shrink_to_fit();
    Tree tree;
    tree.nodes_ = parsed->nodes;
    tree.children_ = parsed->children;
    tree.text_ = parsed->text;
    tree.root_ = parsed->root;
    tree.has_root_ = parsed->has_root;
    tree.storage_ = std::move(parsed);
    return tree;
}

Node Tree::root() const {
    if (!has_root_) return {};
    return {this, root_};
}

bool Node::is_null() const { return tree_ && tree_->nodes_[index_].kind == Tree::Kind::null; }
bool Node::is_scalar() const { return tree_ && tree_->nodes_[index_].kind == Tree::Kind::scalar; }
bool Node::is_sequence() const {
    return tree_ && tree_->nodes_[index_].kind == Tree::Kind::sequence;
}
bool Node::is_map() const { return tree_ && tree_->nodes_[index_].kind == Tree::Kind::map; }

std::string_view Node::scalar() const {
    if (!is_scalar()) return {};
    const auto& node = tree_->nodes_[index_];
    return tree_->text_.substr(node.first, node.count);
}

YAML::Mark Node::mark() const {
    if (!tree_) return YAML::Mark::null_mark();
    const auto& node = tree_->nodes_[index_];
    if (node.line < 0) return YAML::Mark::null_mark();
    YAML::Mark mark;
    mark.line = node.line;
    mark.column = node.column;
    return mark;
}

std::size_t Node::size() const {
    if (is_sequence()) return tree_->nodes_[index_].count;
    if (is_map()) return tree_->nodes_[index_].count / 2;
    return 0;
}

Node Node::item(std::size_t i) const {
    return {tree_, tree_->children_[tree_->nodes_[index_].first + i]};
}

Node Node::key(std::size_t i) const {
    return {tree_, tree_->children_[tree_->nodes_[index_].first + 2 * i]};
}

Node Node::value(std::size_t i) const {
    return {tree_, tree_->children_[tree_->nodes_[index_].first + 2 * i + 1]};
}

Node Node::find(std::string_view wanted) const {
    if (!is_map()) return {};
    for (std::size_t i = 0; i < size(); ++i) {
        const Node k = key(i);
        if (k.is_scalar() && k.scalar() == wanted) return value(i);
    }
    return {};
}

}  // namespace eip2mqtt::adapters::yaml::detail
