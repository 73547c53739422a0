#include "eip2mqtt/core/config/diagnostic.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(Diagnostic, FileLineColumn) {
    const Diagnostic d{{"eip2mqtt.yaml", 12, 5}, "unknown key 'lenght'"};
    EXPECT_EQ(d.to_string(), "eip2mqtt.yaml:12:5: error: unknown key 'lenght'");
}

TEST(Diagnostic, UnknownColumnIsLeftOut) {
    const Diagnostic d{{"points.csv", 3, 0}, "bad address"};
    EXPECT_EQ(d.to_string(), "points.csv:3: error: bad address");
}

TEST(Diagnostic, UnknownLineLeavesOutTheColumnToo) {
    const Diagnostic d{{"eip2mqtt.yaml", 0, 7}, "no exchanges"};
    EXPECT_EQ(d.to_string(), "eip2mqtt.yaml: error: no exchanges");
}

TEST(Diagnostic, NoFile) {
    EXPECT_EQ((Diagnostic{{"", 0, 0}, "oops"}).to_string(), "error: oops");
    EXPECT_EQ((Diagnostic{{"", 4, 2}, "oops"}).to_string(), "4:2: error: oops");
}

TEST(InQuotes, PlainTextIsQuotedAsItIs) {
    EXPECT_EQ(in_quotes("PRESSAO"), "'PRESSAO'");
    EXPECT_EQ(in_quotes("PRESS\xC3\x83O \\n"), "'PRESS\xC3\x83O \\n'");  // UTF-8 and a backslash
    EXPECT_EQ(in_quotes(""), "''");
}

TEST(InQuotes, ControlCharactersAndInvalidUtf8AreEscaped) {
    EXPECT_EQ(in_quotes(std::string("A\0B", 3)), "'A\\x00B'");
    // A NUL before digits: "\012" would read as a newline, another byte.
    EXPECT_EQ(in_quotes(std::string("A\0"
                                    "12",
                                    4)),
              "'A\\x0012'");
    EXPECT_EQ(in_quotes("a\tb\nc\rd"), "'a\\tb\\nc\\rd'");
    EXPECT_EQ(in_quotes("\x1B[2J"), "'\\x1B[2J'");  // a terminal escape sequence stays inert
    EXPECT_EQ(in_quotes("\x7F"), "'\\x7F'");
    EXPECT_EQ(in_quotes("\xC2\x85"), "'\\u0085'");                  // a C1 control
    EXPECT_EQ(in_quotes("\xEF\xBF\xBF"), "'\\uFFFF'");              // a non-character
    EXPECT_EQ(in_quotes("\xF0\x9F\xBF\xBF"), "'\\U0001FFFF'");      // one above the BMP
    EXPECT_EQ(in_quotes(std::string("a\xFF") + "b"), "'a\\xFFb'");  // a stray byte
    EXPECT_EQ(in_quotes("\xC0\xAF"), "'\\xC0\\xAF'");               // overlong '/'
    EXPECT_EQ(in_quotes("\xE2\x82"), "'\\xE2\\x82'");               // cut short
    EXPECT_EQ(in_quotes("\xE2\x82\xAC\n"), "'\xE2\x82\xAC\\n'");    // the euro sign stays
}

TEST(InQuotes, LongTextIsCutWithItsLength) {
    const std::string long_name(70000, 'A');
    EXPECT_EQ(in_quotes(long_name),
              "'" + std::string(max_in_quotes_bytes, 'A') + "...' (70000 bytes)");
    EXPECT_EQ(in_quotes(std::string(max_in_quotes_bytes, 'A')),
              "'" + std::string(max_in_quotes_bytes, 'A') + "'");
    // Never inside a UTF-8 character: a two-byte character across the cut goes whole.
    const std::string accents = std::string(max_in_quotes_bytes - 1, 'A') + "\xC3\x83" + "B";
    EXPECT_EQ(in_quotes(accents), "'" + std::string(max_in_quotes_bytes - 1, 'A') + "...' (" +
                                      std::to_string(accents.size()) + " bytes)");
}

TEST(FileName, CopiesShareOneString) {
    const FileName name("plant/eip2mqtt-turbine-hall.yaml");
    const Mark a{name, 1, 1};
    const Mark b = a;
    // One heap string for every mark of a file, however many marks there are.
    EXPECT_EQ(&a.file.str(), &name.str());
    EXPECT_EQ(&b.file.str(), &name.str());
    EXPECT_EQ(b.file, "plant/eip2mqtt-turbine-hall.yaml");
}

TEST(FileName, ComparesByText) {
    EXPECT_EQ(FileName("a.yaml"), FileName(std::string("a.yaml")));  // made apart, one name
    EXPECT_EQ(&FileName("a.yaml").str(), &FileName("a.yaml").str());
    EXPECT_NE(FileName("a.yaml"), FileName("b.csv"));
    EXPECT_LT(FileName("a.yaml"), FileName("b.csv"));
    EXPECT_EQ(FileName(), FileName(""));
    EXPECT_TRUE(FileName().empty());
    EXPECT_EQ(FileName().str(), "");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
