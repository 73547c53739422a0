// The repository's Markdown pages: every relative link of every page (README.md, docs/, bench/...)
// names a file that exists, and every #anchor a heading of the page it names, by GitHub's rules;
// README.md stays a front page, at most 300 lines, with a line for every page of docs/.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

const fs::path source_dir = EIP2MQTT_SOURCE_DIR;

std::vector<std::string> lines_of(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

/// Every *.md under `root`, leaving out hidden directories (.git), node_modules (third-party
/// packages), build trees (a directory holding CMakeCache.txt) and what .gitignore leaves out at
/// the top, /build*/ (bench/run.sh --against unpacks an older tree in build-bench-against/).
std::vector<fs::path> markdown_pages(const fs::path& root) {
    std::vector<fs::path> pages;
    const auto options = fs::directory_options::skip_permission_denied;
    for (auto it = fs::recursive_directory_iterator(root, options);
         it != fs::recursive_directory_iterator(); ++it) {
        const auto name = it->path().filename().string();
        if (it->is_directory() && (name.starts_with(".") || name == "node_modules" ||
                                   (it.depth() == 0 && name.starts_with("build")) ||
                                   fs::exists(it->path() / "CMakeCache.txt"))) {
            it.disable_recursion_pending();
        } else if (it->is_regular_file() && it->path().extension() == ".md") {
            pages.push_back(it->path());
        }
    }
    std::sort(pages.begin(), pages.end());
    return pages;
}

/// Whether `line` opens or closes a fenced code block (``` or ~~~, indented 3 spaces at most).
bool is_fence(const std::string& line) {
    const auto text = line.find_first_not_of(' ');
    return text != std::string::npos && text <= 3 &&
           (line.compare(text, 3, "```") == 0 || line.compare(text, 3, "~~~") == 0);
}

/// The code point of the UTF-8 sequence at `text[i]`, and its length in bytes.
std::pair<std::uint32_t, std::size_t> code_point(const std::string& text, std::size_t i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const std::size_t length = byte >= 0xF0 ? 4 : byte >= 0xE0 ? 3 : byte >= 0xC0 ? 2 : 1;
    std::uint32_t point = length == 1 ? byte : byte & (0x7F >> length);
    for (std::size_t k = 1; k < length && i + k < text.size(); ++k) {
        point = (point << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    }
    return {point, length};
}

/// GitHub's anchor of a heading: its text as shown (a link's text, not its target), lowercased,
/// each space a '-', and every punctuation character dropped but '-' and '_'. Non-ASCII letters
/// stay; Latin-1 and general punctuation (§, —, ›...) go.
std::string anchor_of(const std::string& heading) {
    static const std::regex link(R"(\[([^\]]*)\]\([^)]*\))");
    const auto text = std::regex_replace(heading, link, "$1");
    std::string anchor;
    for (std::size_t i = 0; i < text.size();) {
        const auto [point, length] = code_point(text, i);
        if (point < 0x80) {
            const auto c = static_cast<char>(point);
            if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') {
                anchor += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            } else if (c == ' ') {
                anchor += '-';
            }
        } else if (!(point <= 0xBF || point == 0xD7 || point == 0xF7 ||
                     (point >= 0x2000 && point <= 0x2BFF))) {
            anchor += text.substr(i, length);
        }
        i += length;
    }
    return anchor;
}

/// The anchors of a page's headings (# to ######, outside code blocks); a heading met again
/// gets -1, -2... as on GitHub.
std::set<std::string> anchors_of(const fs::path& page) {
    static const std::regex heading(R"(^ {0,3}#{1,6}\s+(.*?)(\s+#+)?\s*$)");
    std::set<std::string> anchors;
    std::map<std::string, int> seen;
    bool in_code = false;
    for (const auto& line : lines_of(page)) {
        std::smatch match;
        if (is_fence(line)) {
            in_code = !in_code;
        } else if (!in_code && std::regex_match(line, match, heading)) {
            const auto anchor = anchor_of(match[1]);
            const int times = seen[anchor]++;
            anchors.insert(times == 0 ? anchor : anchor + "-" + std::to_string(times));
        }
    }
    return anchors;
}

struct Link {
    int line = 0;
    std::string target;
};

/// The targets of a page's inline links ([text](target "title")) and link definitions
/// ([name]: target), outside code blocks and code spans.
std::vector<Link> links_of(const fs::path& page) {
    static const std::regex code_span("`[^`]*`");
    static const std::regex inline_link(R"(\]\(\s*<?([^)\s>]+)>?(\s+"[^"]*")?\s*\))");
    static const std::regex definition(R"(^ {0,3}\[[^\]]+\]:\s*<?([^\s>]+)>?)");
    std::vector<Link> links;
    bool in_code = false;
    int number = 0;
    for (const auto& line : lines_of(page)) {
        ++number;
        if (is_fence(line)) in_code = !in_code;
        if (in_code || is_fence(line)) continue;
        const auto text = std::regex_replace(line, code_span, "");
        for (std::sregex_iterator it(text.begin(), text.end(), inline_link), end; it != end; ++it) {
            links.push_back({number, (*it)[1]});
        }
        std::smatch match;
        if (std::regex_search(text, match, definition)) links.push_back({number, match[1]});
    }
    return links;
}

/// What is wrong with one link of `page`, or nothing: a URL with a scheme (https:, mailto:)
/// is not checked; a path must name an existing file or directory, an anchor a heading of the
/// Markdown page it names (the page itself when the path is empty).
std::string problem_of(const fs::path& page, const Link& link) {
    static const std::regex scheme("^[A-Za-z][A-Za-z0-9+.-]*:");
    if (std::regex_search(link.target, scheme)) return "";
    const auto hash = link.target.find('#');
    const auto path = link.target.substr(0, hash);
    const auto target = path.empty() ? page : (page.parent_path() / path).lexically_normal();
    const auto where = page.string() + ":" + std::to_string(link.line) + ": " + link.target;
    if (!fs::exists(target)) return where + ": no such file";
    if (hash == std::string::npos || target.extension() != ".md") return "";
    const auto anchor = link.target.substr(hash + 1);
    if (!anchors_of(target).contains(anchor)) return where + ": no heading #" + anchor;
    return "";
}

/// Every broken link of the pages under `root`, and how many links were checked.
std::pair<std::vector<std::string>, int> broken_links(const fs::path& root) {
    std::vector<std::string> problems;
    int checked = 0;
    for (const auto& page : markdown_pages(root)) {
        for (const auto& link : links_of(page)) {
            ++checked;
            if (auto problem = problem_of(page, link); !problem.empty()) {
                problems.push_back(problem);
            }
        }
    }
    return {problems, checked};
}

std::string joined(const std::vector<std::string>& lines) {
    std::ostringstream text;
    for (const auto& line : lines) text << line << "\n";
    return text.str();
}

TEST(DocsLinks, AnchorsFollowGitHubsRules) {
    EXPECT_EQ(anchor_of("Exchange descriptions: `_meta`"), "exchange-descriptions-_meta");
    EXPECT_EQ(anchor_of("9.7 Address proof"), "97-address-proof");
    EXPECT_EQ(anchor_of("Running it as a service"), "running-it-as-a-service");
    EXPECT_EQ(anchor_of("One tag: `{base}/{exchange}/{tag}/set`"), "one-tag-baseexchangetagset");
    EXPECT_EQ(anchor_of("See [the API](mqtt-api.md) — §9"), "see-the-api--9");
    EXPECT_EQ(anchor_of("Pressão"), "pressão");
}

TEST(DocsLinks, TheCheckerFindsAMissingFileAMissingHeadingAndSkipsCode) {
    TempDir dir;
    fs::create_directories(fs::path(dir.path()) / "docs");
    dir.write("README.md",
              "# Title\n\n## A section\n\n[ok](docs/page.md#a-heading) [self](#a-section)\n"
              "[gone](docs/missing.md) [wrong](docs/page.md#no-such-heading)\n"
              "[web](https://example.com/x.md) `[code](not/checked.md)`\n"
              "```\n[fenced](not/checked/either.md)\n# not a heading\n```\n"
              "[def]: docs/also-missing.md\n");
    dir.write("docs/page.md", "# Page\n\n## A heading\n\n[up](../README.md#title)\n");
    fs::create_directories(fs::path(dir.path()) / "node_modules");
    dir.write("node_modules/other.md", "[never read](nowhere.md)\n");
    fs::create_directories(fs::path(dir.path()) / "build-bench-against");
    dir.write("build-bench-against/old.md", "[never read](nowhere.md)\n");

    const auto [problems, checked] = broken_links(dir.path());
    EXPECT_EQ(checked, 7);
    ASSERT_EQ(problems.size(), 3u) << joined(problems);
    EXPECT_TRUE(problems[0].ends_with("docs/missing.md: no such file")) << problems[0];
    EXPECT_TRUE(problems[1].ends_with("no heading #no-such-heading")) << problems[1];
    EXPECT_TRUE(problems[2].ends_with("docs/also-missing.md: no such file")) << problems[2];
}

TEST(DocsLinks, EveryRelativeLinkOfEveryPageResolves) {
    const auto pages = markdown_pages(source_dir);
    ASSERT_TRUE(std::find(pages.begin(), pages.end(), source_dir / "README.md") != pages.end());
    const auto [problems, checked] = broken_links(source_dir);
    EXPECT_GT(checked, 100) << "the pages' links were not found";
    EXPECT_TRUE(problems.empty()) << joined(problems);
}

TEST(DocsLinks, TheReadmeIsAFrontPageOfAtMost300Lines) {
    EXPECT_LE(lines_of(source_dir / "README.md").size(), 300u);
}

TEST(DocsLinks, TheReadmesMapHasALineForEveryPageOfDocs) {
    std::set<std::string> mapped;
    for (const auto& link : links_of(source_dir / "README.md")) mapped.insert(link.target);
    for (const auto& entry : fs::directory_iterator(source_dir / "docs")) {
        if (entry.path().extension() != ".md") continue;
        const auto name = "docs/" + entry.path().filename().string();
        EXPECT_TRUE(mapped.contains(name)) << name << " is not on the README's map of docs/";
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
