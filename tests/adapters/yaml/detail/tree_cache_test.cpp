#include <gtest/gtest.h>
#include <sys/stat.h>
#include <yaml-cpp/exceptions.h>

#include <fstream>
#include <iterator>
#include <string>

#include "adapters/yaml/detail/syntax_cache.hpp"
#include "adapters/yaml/detail/tree.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

const std::string kText =
    "gateway: { id: gw }\n"
    "base: &b\n"
    "  x: 1\n"
    "copy: *b\n"
    "list:\n"
    "  - { name: A, address: \"1.0\" }\n"
    "  - [x, ~]\n"
    "empty:\n";

/// Everything a reader of a Tree can see, as text: kinds, scalars, marks, order.
std::string dump(const Node& node) {
    std::string out = std::to_string(node.mark().line) + ":" + std::to_string(node.mark().column);
    if (node.is_null()) return out + " null";
    if (node.is_scalar()) return out + " '" + std::string(node.scalar()) + "'";
    out += node.is_map() ? " {" : " [";
    for (std::size_t i = 0; i < node.size(); ++i) {
        out += node.is_map() ? dump(node.key(i)) + "=" + dump(node.value(i)) : dump(node.item(i));
        out += ", ";
    }
    return out + (node.is_map() ? "}" : "]");
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

class TreeCache : public ::testing::Test {
protected:
    test::TempDir dir;
    std::string file = dir.path() + "/config.tree";
};

TEST_F(TreeCache, ASavedTreeLoadsAsItWasParsed) {
    const Tree parsed = Tree::parse(kText);
    ASSERT_EQ(parsed.save(file, kText), "");
    std::string why;
    const auto loaded = Tree::load(file, kText, why);
    ASSERT_TRUE(loaded) << why;
    EXPECT_EQ(why, "");
    EXPECT_EQ(dump(loaded->root()), dump(parsed.root()));
    EXPECT_EQ(loaded->root().find("copy").find("x").scalar(), "1");
}

TEST_F(TreeCache, AnEmptyDocumentHasNoRootAfterLoadingEither) {
    ASSERT_EQ(Tree::parse("# nothing\n").save(file, "# nothing\n"), "");
    std::string why;
    const auto loaded = Tree::load(file, "# nothing\n", why);
    ASSERT_TRUE(loaded) << why;
    EXPECT_FALSE(loaded->root().is_defined());
}

TEST_F(TreeCache, OnlyTheOwnerMayReadIt) {
    // The configuration may hold a password: the cache is no more readable than necessary.
    ASSERT_EQ(Tree::parse(kText).save(file, kText), "");
    struct stat st {};
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
}

TEST_F(TreeCache, AMissingFileIsNoTreeAndNoComplaint) {
    std::string why = "stale";
    EXPECT_FALSE(Tree::load(file, kText, why));
    EXPECT_EQ(why, "");
}

TEST_F(TreeCache, AnyChangedByteOfTheTextIsAnotherConfiguration) {
    ASSERT_EQ(Tree::parse(kText).save(file, kText), "");
    std::string why;
    std::string edited = kText;
    edited[edited.find("1.0") + 2] = '1';  // same length, one byte apart
    EXPECT_FALSE(Tree::load(file, edited, why));
    EXPECT_EQ(why, "the configuration changed");
    EXPECT_FALSE(Tree::load(file, kText + "\n", why));
    EXPECT_EQ(why, "the configuration changed");
}

TEST_F(TreeCache, ATruncatedFileIsDamaged) {
    ASSERT_EQ(Tree::parse(kText).save(file, kText), "");
    const auto bytes = read_file(file);
    write_file(file, bytes.substr(0, bytes.size() - 1));
    std::string why;
    EXPECT_FALSE(Tree::load(file, kText, why));
    EXPECT_EQ(why, "damaged (its sizes do not add up)");
    write_file(file, bytes.substr(0, 10));
    EXPECT_FALSE(Tree::load(file, kText, why));
    EXPECT_EQ(why, "not a saved tree");
}

TEST_F(TreeCache, IndicesOutsideTheTreeAreDamageNotAccesses) {
    ASSERT_EQ(Tree::parse(kText).save(file, kText), "");
    auto bytes = read_file(file);
    // Everything after the stored text (nodes, children, scalars) overwritten: sizes still add
    // up, but kinds and indices point nowhere.
    const auto text_end = bytes.find(kText) + kText.size();
    ASSERT_LT(text_end, bytes.size());
    for (auto i = text_end; i < bytes.size(); ++i) bytes[i] = '\xff';
    write_file(file, bytes);
    std::string why;
    EXPECT_FALSE(Tree::load(file, kText, why));
    EXPECT_EQ(why, "damaged (its nodes are inconsistent)");
}

TEST_F(TreeCache, AnotherFileIsNotATree) {
    write_file(file, kText);
    std::string why;
    EXPECT_FALSE(Tree::load(file, kText, why));
    EXPECT_EQ(why, "not a saved tree");
}

TEST_F(TreeCache, SavingIntoAMissingDirectorySaysWhatFailed) {
    const auto failed = Tree::parse(kText).save(dir.path() + "/no/such/dir/c.tree", kText);
    EXPECT_NE(failed.find("open "), std::string::npos) << failed;
    EXPECT_NE(failed.find("No such file or directory"), std::string::npos) << failed;
}

TEST_F(TreeCache, ParseWithCacheSavesThenUsesTheSavedTree) {
    const std::string config = dir.path() + "/gw.yaml";
    const auto cache = dir.path() + "/cache";  // created on first use
    const auto saved = syntax_cache_file(cache, config);
    EXPECT_EQ(saved.parent_path(), cache);
    EXPECT_EQ(saved.filename().string().rfind("gw.yaml-", 0), 0u) << saved;

    const Tree first = parse_with_cache(kText, config, cache);
    EXPECT_EQ(dump(first.root()), dump(Tree::parse(kText).root()));
    std::string why;
    ASSERT_TRUE(Tree::load(saved, kText, why)) << why;

    // Proof that the next call reads the file and does not parse: a tree saved for kText that
    // kText does not parse into.
    ASSERT_EQ(Tree::parse("other: tree\n").save(saved, kText), "");
    EXPECT_EQ(parse_with_cache(kText, config, cache).root().find("other").scalar(), "tree");

    // Another text is parsed, and replaces the saved tree.
    const std::string edited = kText + "more: 2\n";
    EXPECT_EQ(parse_with_cache(edited, config, cache).root().find("more").scalar(), "2");
    EXPECT_TRUE(Tree::load(saved, edited, why)) << why;
}

TEST_F(TreeCache, ParseWithCacheKeepsConfigurationsOfTheSameNameApart) {
    const auto cache = dir.path() + "/cache";
    EXPECT_NE(syntax_cache_file(cache, dir.path() + "/a/gw.yaml"),
              syntax_cache_file(cache, dir.path() + "/b/gw.yaml"));
}

TEST_F(TreeCache, ASyntaxErrorThrowsAndSavesNothing) {
    const std::string config = dir.path() + "/gw.yaml";
    const auto cache = dir.path() + "/cache";
    EXPECT_THROW(parse_with_cache("a: [1, 2\n", config, cache), YAML::Exception);
    std::string why;
    EXPECT_FALSE(Tree::load(syntax_cache_file(cache, config), "a: [1, 2\n", why));
    EXPECT_EQ(why, "");
}

TEST_F(TreeCache, AnUnwritableCacheStillParses) {
    const std::string config = dir.path() + "/gw.yaml";
    const auto blocker = dir.write("file", "not a directory");
    const Tree tree = parse_with_cache(kText, config, blocker + "/cache");
    EXPECT_EQ(dump(tree.root()), dump(Tree::parse(kText).root()));
}

}  // namespace
}  // namespace eip2mqtt::adapters::yaml::detail
