#include "adapters/yaml/detail/tree.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <stop_token>
#include <string>

namespace eip2mqtt::adapters::yaml::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(YamlTree, MapsKeepEntriesInDocumentOrder) {
    const auto tree = Tree::parse("b: 1\na: two\nc: '3'\n");
    const Node root = tree.root();
    ASSERT_TRUE(root.is_map());
    ASSERT_EQ(root.size(), 3u);
    EXPECT_EQ(root.key(0).scalar(), "b");
    EXPECT_EQ(root.value(0).scalar(), "1");
    EXPECT_EQ(root.key(1).scalar(), "a");
    EXPECT_EQ(root.value(1).scalar(), "two");
    EXPECT_EQ(root.key(2).scalar(), "c");
    EXPECT_EQ(root.value(2).scalar(), "3");
    EXPECT_EQ(root.find("a").scalar(), "two");
    EXPECT_FALSE(root.find("z").is_defined());
    EXPECT_FALSE(root.find("z").is_null());  // undefined is not null, as in YAML::Node
}

TEST(YamlTree, AStopRequestedEndsTheParseWithCancelled) {
    std::string text;
    for (int i = 0; i < 5000; ++i)
        text += "k" + std::to_string(i) + ": " + std::to_string(i) + "\n";
    std::stop_source stop;
    EXPECT_EQ(Tree::parse(text, stop.get_token()).root().size(), 5000u);
    stop.request_stop();
    EXPECT_THROW(Tree::parse(text, stop.get_token()), Tree::Cancelled);
}

TEST(YamlTree, NestedSequencesAndMapsAndFlowStyle) {
    const auto tree = Tree::parse(
        "list:\n"
        "  - { name: A, address: \"1.0\" }\n"
        "  - [x, y]\n"
        "  - plain\n"
        "after: end\n");
    const Node list = tree.root().find("list");
    ASSERT_TRUE(list.is_sequence());
    ASSERT_EQ(list.size(), 3u);
    EXPECT_TRUE(list.item(0).is_map());
    EXPECT_EQ(list.item(0).find("address").scalar(), "1.0");
    ASSERT_TRUE(list.item(1).is_sequence());
    EXPECT_EQ(list.item(1).size(), 2u);
    EXPECT_EQ(list.item(1).item(1).scalar(), "y");
    EXPECT_TRUE(list.item(2).is_scalar());
    EXPECT_EQ(list.item(2).size(), 0u);
    EXPECT_EQ(tree.root().find("after").scalar(), "end");
}

TEST(YamlTree, NullsAreNullNotScalars) {
    const auto tree = Tree::parse("a:\nb: ~\nc: null\nd: 'null'\ne: ''\n");
    const Node root = tree.root();
    EXPECT_TRUE(root.find("a").is_null());
    EXPECT_TRUE(root.find("b").is_null());
    EXPECT_TRUE(root.find("c").is_null());
    EXPECT_FALSE(root.find("a").is_scalar());
    EXPECT_EQ(root.find("a").scalar(), "");
    EXPECT_TRUE(root.find("d").is_scalar());  // quoted: the text null, as yaml-cpp reads it
    EXPECT_EQ(root.find("d").scalar(), "null");
    EXPECT_TRUE(root.find("e").is_scalar());
    EXPECT_EQ(root.find("e").scalar(), "");
}

TEST(YamlTree, AliasesAreTheAnchoredNodeWithItsMark) {
    const auto tree = Tree::parse(
        "base: &b\n"
        "  x: 1\n"
        "copy: *b\n"
        "name: &n hello\n"
        "again: *n\n");
    const Node root = tree.root();
    const Node copy = root.find("copy");
    ASSERT_TRUE(copy.is_map());
    EXPECT_EQ(copy.find("x").scalar(), "1");
    EXPECT_EQ(copy.mark().line, root.find("base").mark().line);
    EXPECT_EQ(copy.mark().column, root.find("base").mark().column);
    EXPECT_EQ(root.find("again").scalar(), "hello");
    EXPECT_EQ(root.find("again").mark().line, 3);
}

TEST(YamlTree, MarksAreYamlCppsZeroBasedLineAndColumn) {
    const auto tree = Tree::parse(
        "gateway:\n"
        "  id: gw\n"
        "exchanges:\n"
        "  - { name: e1, tags: [ { name: T } ] }\n");
    const Node root = tree.root();
    EXPECT_EQ(root.key(0).mark().line, 0);
    EXPECT_EQ(root.key(0).mark().column, 0);
    const Node id_key = root.value(0).key(0);
    EXPECT_EQ(id_key.mark().line, 1);
    EXPECT_EQ(id_key.mark().column, 2);
    const Node exchange = root.find("exchanges").item(0);
    EXPECT_EQ(exchange.mark().line, 3);
    EXPECT_EQ(exchange.mark().column, 4);
    const Node tag = exchange.find("tags").item(0);
    EXPECT_EQ(tag.key(0).mark().line, 3);
    EXPECT_EQ(tag.key(0).mark().column, 26);
    EXPECT_TRUE(Node().mark().is_null());
}

TEST(YamlTree, DuplicateKeysAreKeptAndFindReturnsTheFirst) {
    const auto tree = Tree::parse("a: 1\na: 2\n");
    const Node root = tree.root();
    ASSERT_EQ(root.size(), 2u);
    EXPECT_EQ(root.value(1).scalar(), "2");
    EXPECT_EQ(root.find("a").scalar(), "1");
}

TEST(YamlTree, NonScalarKeysAreKeptAndNeverFound) {
    const auto tree = Tree::parse("? [a]\n: 1\nb: 2\n");
    const Node root = tree.root();
    ASSERT_EQ(root.size(), 2u);
    EXPECT_TRUE(root.key(0).is_sequence());
    EXPECT_EQ(root.find("b").scalar(), "2");
    EXPECT_FALSE(root.find("a").is_defined());
}

/// The same document read by YAML::Load, node by node: kinds, scalar text, marks and order.
void expect_same(const Node& mine, const YAML::Node& theirs, const std::string& path) {
    SCOPED_TRACE(path);
    ASSERT_EQ(mine.is_null(), theirs.IsNull());
    ASSERT_EQ(mine.is_scalar(), theirs.IsScalar());
    ASSERT_EQ(mine.is_sequence(), theirs.IsSequence());
    ASSERT_EQ(mine.is_map(), theirs.IsMap());
    EXPECT_EQ(mine.mark().line, theirs.Mark().line);
    EXPECT_EQ(mine.mark().column, theirs.Mark().column);
    if (theirs.IsScalar()) {
        EXPECT_EQ(mine.scalar(), theirs.Scalar());
    }
    ASSERT_EQ(mine.size(), theirs.size());
    std::size_t i = 0;
    if (theirs.IsSequence()) {
        for (const auto& item : theirs) {
            expect_same(mine.item(i), item, path + "/" + std::to_string(i));
            ++i;
        }
    } else if (theirs.IsMap()) {
        for (const auto& entry : theirs) {
            expect_same(mine.key(i), entry.first, path + "/key" + std::to_string(i));
            expect_same(mine.value(i), entry.second, path + "/value" + std::to_string(i));
            ++i;
        }
    }
}

TEST(YamlTree, ReadsAConfigurationAsYamlLoadDoes) {
    const std::string text =
        "gateway: { id: gw, log_level: info }\n"
        "mqtt:\n"
        "  url: tcp://localhost:1883   # comment\n"
        "  tls:\n"
        "  version: 3.1.1\n"
        "defaults: &d { type: dint, unit: \"bar\" }\n"
        "exchanges:\n"
        "  - name: e1\n"
        "    tags:\n"
        "      - { name: A, address: 126.0, type: int, initial: -2 }\n"
        "      - name: B\n"
        "        address: '1.7'\n"
        "        description: |\n"
        "          two\n"
        "          lines\n"
        "      - *d\n"
        "      - ~\n"
        "  - [1, 2, [3, {x: y}]]\n";
    const auto tree = Tree::parse(text);
    expect_same(tree.root(), YAML::Load(text), "");
}

TEST(YamlTree, EmptyTextHasNoRoot) {
    EXPECT_FALSE(Tree::parse("").root().is_defined());
    EXPECT_FALSE(Tree::parse("# only a comment\n").root().is_defined());
    EXPECT_TRUE(Tree::parse("~\n").root().is_null());
}

TEST(YamlTree, OnlyTheFirstDocumentIsRead) {
    const auto tree = Tree::parse("a: 1\n---\nb: 2\n");
    EXPECT_EQ(tree.root().find("a").scalar(), "1");
    EXPECT_FALSE(tree.root().find("b").is_defined());
}

TEST(YamlTree, SyntaxErrorsThrowWithTheirMark) {
    try {
        (void)Tree::parse("a: 1\nb: [1, 2\n");
        FAIL() << "expected a YAML::ParserException";
    } catch (const YAML::ParserException& e) {
        EXPECT_FALSE(e.mark.is_null());
        EXPECT_GE(e.mark.line, 1);
    }
    EXPECT_THROW((void)Tree::parse("a: *unknown\n"), YAML::ParserException);
}

TEST(YamlTree, UndefinedNodesAnswerEverythingEmpty) {
    const Node none;
    EXPECT_FALSE(none.is_defined());
    EXPECT_FALSE(none.is_null());
    EXPECT_FALSE(none.is_map());
    EXPECT_FALSE(none.is_sequence());
    EXPECT_FALSE(none.is_scalar());
    EXPECT_EQ(none.size(), 0u);
    EXPECT_EQ(none.scalar(), "");
    EXPECT_FALSE(none.find("a").is_defined());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml::detail
