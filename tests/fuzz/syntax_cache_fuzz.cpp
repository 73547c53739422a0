// Fuzzes the reader of the YAML syntax cache (Tree::load): whatever bytes a cache file holds,
// loading must refuse it or give a tree whose every index stays inside its arrays, never crash.
// The input patches a tree saved for a small configuration (3 bytes per patch: offset low and
// high byte, new value), so that the fuzzer gets past the header checks to the nodes.

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "adapters/yaml/detail/tree.hpp"

namespace {

using eip2mqtt::adapters::yaml::detail::Node;
using eip2mqtt::adapters::yaml::detail::Tree;

const std::string kText =
    "gateway: { id: gw }\n"
    "base: &b { x: 1, y: [a, ~] }\n"
    "copy: *b\n"
    "exchanges:\n"
    "  - { name: e, tags: [ { name: t, address: \"0.0\", type: dint } ] }\n";

/// A saved tree of kText in a private directory, removed at exit.
struct Saved {
    Saved() {
        char pattern[] = "/tmp/eip2mqtt-fuzz-XXXXXX";
        dir = ::mkdtemp(pattern);
        file = dir / "fuzz.tree";
        if (!Tree::parse(kText).save(file, kText).empty()) __builtin_trap();
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    ~Saved() { std::filesystem::remove_all(dir); }
    std::filesystem::path dir;
    std::filesystem::path file;
    std::string bytes;
};

/// Reads every part of a loaded tree; `budget` bounds the walk (aliases may form cycles).
void walk(const Node& node, int& budget) {
    if (--budget < 0) return;
    (void)node.is_null();
    (void)node.mark();
    (void)node.scalar().size();
    (void)node.find("x");
    for (std::size_t i = 0; i < node.size(); ++i) {
        if (node.is_map()) {
            walk(node.key(i), budget);
            walk(node.value(i), budget);
        } else {
            walk(node.item(i), budget);
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const Saved saved;
    std::string bytes = saved.bytes;
    for (std::size_t i = 0; i + 3 <= size; i += 3) {
        const std::size_t offset = (data[i] | std::size_t{data[i + 1]} << 8) % bytes.size();
        bytes[offset] = static_cast<char>(data[i + 2]);
    }
    std::ofstream(saved.file, std::ios::binary | std::ios::trunc) << bytes;
    std::string why;
    const auto tree = Tree::load(saved.file, kText, why);
    if (tree) {
        int budget = 10000;
        walk(tree->root(), budget);
    } else if (why.empty()) {
        __builtin_trap();  // the file exists: a refusal always says why
    }
    return 0;
}
