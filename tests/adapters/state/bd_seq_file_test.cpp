// BdSeqFile: the Sparkplug bdSeq kept across restarts: what was written is read back, a file
// that is missing or holds no bdSeq reads as none (the node then starts at 0), and a directory
// it cannot write in costs the continuity, never the gateway.

#include "eip2mqtt/adapters/state/bd_seq_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace eip2mqtt::adapters::state {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

class BdSeqFileTest : public ::testing::Test {
protected:
    BdSeqFileTest()
        : dir_(fs::temp_directory_path() /
               ("eip2mqtt_bd_seq_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()))) {
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    ~BdSeqFileTest() override { fs::remove_all(dir_); }

    std::string path() const { return (dir_ / "sparkplug-bdseq").string(); }
    void write_text(const std::string& text) const { std::ofstream(path()) << text; }
    std::string read_text() const {
        std::ifstream in(path());
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    fs::path dir_;
};

TEST_F(BdSeqFileTest, WhatWasWrittenIsReadBackAsOneLineOfText) {
    BdSeqFile file(path());
    EXPECT_EQ(file.read(), std::nullopt);  // none yet: the first will takes 0
    file.write(0);
    EXPECT_EQ(file.read(), 0);
    file.write(255);
    EXPECT_EQ(read_text(), "255\n");
    EXPECT_EQ(BdSeqFile(path()).read(), 255);  // another process's read
}

TEST_F(BdSeqFileTest, AFileThatHoldsNoBdSeqReadsAsNone) {
    BdSeqFile file(path());
    for (const std::string text : {"", "256\n", "-1\n", "12 \n", "twelve\n", "12\n13\n", "1.5"}) {
        write_text(text);
        EXPECT_EQ(file.read(), std::nullopt) << text;
    }
    write_text("12");  // without its newline
    EXPECT_EQ(file.read(), 12);
}

TEST_F(BdSeqFileTest, ADirectoryItCannotWriteInLeavesTheOldValueAndGoesOn) {
    BdSeqFile file(path());
    file.write(7);
    BdSeqFile nowhere((dir_ / "missing" / "sparkplug-bdseq").string());
    nowhere.write(8);  // logged, not thrown
    nowhere.write(9);
    EXPECT_EQ(nowhere.read(), std::nullopt);
    EXPECT_EQ(file.read(), 7);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::state
