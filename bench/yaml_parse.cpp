// yaml_parse: the floor of inline-YAML start-up: yaml-cpp's own parser reading a configuration
// file with an event handler that does nothing. The gateway cannot start faster than this while
// it parses that file with yaml-cpp (a project rule), whatever it builds from the events.
//
// Reads --file into memory once, then parses it --repeat times (default 3); prints the median
// and the fastest wall time of one parse, in ms, and the file size.

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "bench_common.hpp"

namespace {

class Ignore : public YAML::EventHandler {
public:
    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
};

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(argc, argv, {"file", "repeat"});
    const std::string path = opt.str("file", "");
    if (path.empty()) bench::Options::fail("--file is required");
    std::ifstream in(path, std::ios::binary);
    if (!in) bench::Options::fail("cannot read " + path);
    std::ostringstream content;
    content << in.rdbuf();
    const std::string text = content.str();

    const auto repeat = static_cast<int>(opt.num("repeat", 3));
    std::vector<double> times;
    for (int i = 0; i < repeat; ++i) {
        const auto start = bench::mono_ns();
        std::istringstream stream(text);  // as the gateway's loader feeds yaml-cpp
        YAML::Parser parser(stream);
        Ignore ignore;
        parser.HandleNextDocument(ignore);
        times.push_back(static_cast<double>(bench::mono_ns() - start) / 1e6);
    }
    const double fastest = *std::min_element(times.begin(), times.end());
    const double median = bench::percentile(times, 0.5);
    std::printf("{\"bytes\":%zu,\"median_ms\":%.1f,\"fastest_ms\":%.1f,\"repeat\":%d}\n",
                text.size(), median, fastest, repeat);
    return 0;
}
