// StateDirLock: the state directory is created, locked and named by its holder; a second
// holder, a directory that cannot be created and one that cannot be written are refused with a
// message that names the directory and the reason.

#include "eip2mqtt/adapters/state/state_dir_lock.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "tests/support/tmpfs.hpp"

namespace eip2mqtt::adapters::state {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

std::string read_all(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The message StateDirLock throws for `directory`, or nullopt when it takes the lock.
std::optional<std::string> refusal(const std::string& directory) {
    try {
        StateDirLock lock(directory, {"gw2", "/etc/second.yaml"});
        return std::nullopt;
    } catch (const std::runtime_error& e) {
        return std::string(e.what());
    }
}

class StateDirLockTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() / ("eip2mqtt_state_dir_" + std::string(info->name()) +
                                             "_" + std::to_string(::getpid()));
        fs::remove_all(root_);
        fs::create_directories(root_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(root_, ignored);
    }
    fs::path root_;
};

TEST_F(StateDirLockTest, CreatesTheDirectoryAndWritesWhoHoldsIt) {
    const auto directory = (root_ / "a" / "state").string();
    StateDirLock lock(directory, {"gw1", "/etc/eip2mqtt/first.yaml"});
    EXPECT_TRUE(fs::is_directory(directory));
    EXPECT_EQ(lock.path(), directory + "/eip2mqtt.lock");
    const auto text = read_all(lock.path());
    EXPECT_NE(text.find("pid " + std::to_string(::getpid()) + "\n"), std::string::npos) << text;
    EXPECT_NE(text.find("gateway_id gw1\n"), std::string::npos) << text;
    EXPECT_NE(text.find("config /etc/eip2mqtt/first.yaml\n"), std::string::npos) << text;
    // The check that the directory is writable leaves nothing behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(directory), fs::directory_iterator()), 1);
}

TEST_F(StateDirLockTest, ASecondHolderIsRefusedWithTheFirstOnesDetails) {
    const auto directory = (root_ / "state").string();
    {
        StateDirLock first(directory, {"gw1", "/etc/eip2mqtt/first.yaml"});
        const auto refused = refusal(directory);
        ASSERT_TRUE(refused.has_value());
        EXPECT_NE(refused->find("gateway.state_dir " + directory +
                                " is in use by another "
                                "eip2mqtt (pid " +
                                std::to_string(::getpid()) +
                                ", gateway.id gw1, config /etc/eip2mqtt/first.yaml, started "),
                  std::string::npos)
            << *refused;
        EXPECT_NE(refused->find("each gateway needs a state_dir of its own"), std::string::npos)
            << *refused;
    }
    // Released with its holder: the file stays, the next one takes it and names itself.
    EXPECT_EQ(refusal(directory), std::nullopt);
}

TEST_F(StateDirLockTest, APathThatCannotBeADirectoryIsRefused) {
    const auto file = root_ / "file";
    { std::ofstream(file) << "x"; }
    EXPECT_EQ(refusal(file.string()), "gateway.state_dir " + file.string() + " is not a directory");
    const auto under = (file / "state").string();
    const auto refused = refusal(under);
    ASSERT_TRUE(refused.has_value());
    EXPECT_EQ(refused->rfind("gateway.state_dir " + under + " cannot be created: ", 0), 0u)
        << *refused;
}

TEST_F(StateDirLockTest, AReadOnlyFileSystemIsRefused) {
    test::Tmpfs read_only(64 * 1024, true);
    if (!read_only.mounted()) GTEST_SKIP() << read_only.error();
    const auto refused = refusal(read_only.path());
    ASSERT_TRUE(refused.has_value());
    EXPECT_EQ(*refused, "gateway.state_dir " + read_only.path() + " is not writable: cannot open " +
                            read_only.path() +
                            "/eip2mqtt.lock (Read-only file system); it must belong to the user "
                            "the gateway runs as (systemd: StateDirectory=)");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::state
