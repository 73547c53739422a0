// A secret the configuration names: a systemd credential by name where the unit has them, else
// a file by path, its first line; what cannot be read is said with the key that named it.

#include "app/detail/secret_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

class SecretFileTest : public ::testing::Test {
protected:
    SecretFileTest()
        : dir_(fs::temp_directory_path() / ("eip2mqtt_secret_" + std::to_string(::getpid()))) {
        fs::create_directories(dir_ / "credentials");
        ::unsetenv("CREDENTIALS_DIRECTORY");
    }
    ~SecretFileTest() override {
        ::unsetenv("CREDENTIALS_DIRECTORY");
        fs::remove_all(dir_);
    }
    static void write(const fs::path& path, const std::string& text) {
        std::ofstream(path) << text;
        fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    }
    /// What read_secret_file throws, or "" when it reads.
    static std::string error_of(const std::string& file, std::string_view key) {
        try {
            (void)read_secret_file(file, key);
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    }

    fs::path dir_;
};

TEST_F(SecretFileTest, APathGivesItsFirstLine) {
    write(dir_ / "password", "s3cret\nsecond line\n");
    EXPECT_EQ(read_secret_file((dir_ / "password").string(), "metrics.auth.password_file"),
              "s3cret");
}

TEST_F(SecretFileTest, ANameIsTheUnitsCredentialOfThatName) {
    write(dir_ / "credentials" / "status-password", "from-credential\n");
    ::setenv("CREDENTIALS_DIRECTORY", (dir_ / "credentials").c_str(), 1);
    EXPECT_EQ(read_secret_file("status-password", "metrics.auth.password_file"), "from-credential");
    EXPECT_EQ(error_of("other", "metrics.auth.password_file"),
              "cannot read metrics.auth.password_file: the systemd credential other (" +
                  (dir_ / "credentials" / "other").string() +
                  "); the unit needs LoadCredential=other");
}

TEST_F(SecretFileTest, WhatCannotBeReadIsSaidWithItsKey) {
    const auto missing = (dir_ / "missing").string();
    EXPECT_EQ(error_of(missing, "metrics.auth.password_file"),
              "cannot read metrics.auth.password_file " + missing);
    EXPECT_EQ(error_of("status-password", "metrics.auth.password_file"),
              "cannot read metrics.auth.password_file status-password (a name without a slash is "
              "a systemd credential only where $CREDENTIALS_DIRECTORY is set, in a unit with "
              "LoadCredential=status-password)");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
