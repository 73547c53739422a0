// ImageFile: two slots overwritten in place in turn; the newest slot that checks out is read;
// a full disk, a torn slot, a removed file or a file of the format before slots cost no image.

#include "eip2mqtt/adapters/state/image_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "adapters/state/detail/image_format.hpp"
#include "tests/support/tmpfs.hpp"

namespace eip2mqtt::adapters::state {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;

constexpr std::uint64_t fingerprint = 0x1234;
constexpr std::size_t length = 6;

std::vector<std::byte> image(unsigned seed) {
    std::vector<std::byte> bytes(length);
    for (std::size_t i = 0; i < length; ++i) bytes[i] = static_cast<std::byte>(i * 3 + seed);
    return bytes;
}

std::vector<char> read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_all(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

ino_t inode_of(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st.st_ino;
}

class ImageFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_image_file_" + std::string(info->name()) +
                                            "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        path_ = (dir_ / "sp.image").string();
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    ImageFile open() const { return ImageFile(path_, "sp", fingerprint, length); }

    fs::path dir_;
    std::string path_;
};

TEST_F(ImageFileTest, SavesOverwriteTheSameFileInPlaceAndTheNewestWins) {
    {
        auto file = open();
        EXPECT_FALSE(file.loaded());
        EXPECT_FALSE(file.in_place());
        ASSERT_EQ(file.save(image(1)), std::nullopt);  // creates the file
    }
    const auto inode = inode_of(path_);
    auto file = open();
    ASSERT_TRUE(file.in_place());
    EXPECT_EQ(file.loaded(), image(1));
    for (unsigned i = 2; i <= 5; ++i) ASSERT_EQ(file.save(image(i)), std::nullopt);
    EXPECT_EQ(inode_of(path_), inode);  // never replaced: overwritten
    EXPECT_EQ(fs::file_size(path_), detail::slotted_file_size);
    EXPECT_EQ(open().loaded(), image(5));
}

TEST_F(ImageFileTest, ATornSlotLeavesTheSaveBeforeIt) {
    {
        auto file = open();
        ASSERT_EQ(file.save(image(1)), std::nullopt);  // slot 0
    }
    {
        auto file = open();
        ASSERT_EQ(file.save(image(2)), std::nullopt);  // slot 1, in place
    }
    auto bytes = read_all(path_);
    ASSERT_EQ(open().loaded(), image(2));
    bytes[detail::slot_size + 44] = static_cast<char>(bytes[detail::slot_size + 44] ^ 0x40);
    write_all(path_, bytes);
    auto file = open();
    EXPECT_EQ(file.loaded(), image(1));
    EXPECT_TRUE(file.in_place());
    // The next save overwrites the torn slot, not the good one.
    ASSERT_EQ(file.save(image(3)), std::nullopt);
    EXPECT_EQ(open().loaded(), image(3));
    bytes = read_all(path_);
    EXPECT_EQ(detail::decode_slot(std::as_bytes(std::span(bytes)).first(detail::slot_size))->data,
              image(1));
}

TEST_F(ImageFileTest, AFileOfTheFormatBeforeSlotsIsReadThenRewrittenWithSlots) {
    // Format 1, as the builds before slots wrote it.
    const auto data = image(7);
    std::vector<std::byte> old;
    const std::string magic = "EIP2MQTT-IMG";
    for (const char c : magic) old.push_back(static_cast<std::byte>(c));
    const auto put = [&](std::uint64_t value, int bytes) {
        for (int i = 0; i < bytes; ++i) old.push_back(static_cast<std::byte>(value >> (8 * i)));
    };
    put(1, 4);
    put(fingerprint, 8);
    put(length, 4);
    put(detail::fnv1a(data), 8);
    old.insert(old.end(), data.begin(), data.end());
    {
        std::ofstream out(path_, std::ios::binary);
        out.write(reinterpret_cast<const char*>(old.data()), static_cast<long>(old.size()));
    }
    auto file = open();
    EXPECT_EQ(file.loaded(), data);
    EXPECT_FALSE(file.in_place());
    ASSERT_EQ(file.save(data), std::nullopt);
    EXPECT_EQ(fs::file_size(path_), detail::slotted_file_size);
    EXPECT_TRUE(open().in_place());
    EXPECT_EQ(open().loaded(), data);
}

TEST_F(ImageFileTest, AFileRemovedWhileOpenIsWrittenAgainByTheNextSave) {
    auto file = open();
    ASSERT_EQ(file.save(image(1)), std::nullopt);
    fs::remove(path_);  // a state directory cleaned by hand
    ASSERT_EQ(file.save(image(2)), std::nullopt);
    EXPECT_EQ(open().loaded(), image(2));
    ASSERT_EQ(file.save(image(3)), std::nullopt);  // in place again, in the new file
    EXPECT_EQ(open().loaded(), image(3));
}

TEST_F(ImageFileTest, AFifoInItsPlaceIsIgnoredWithoutHanging) {
    ASSERT_EQ(::mkfifo(path_.c_str(), 0600), 0);
    const auto file = open();  // a blocking open or read would never return
    EXPECT_FALSE(file.loaded());
    EXPECT_FALSE(file.in_place());
}

TEST_F(ImageFileTest, OnAFullDiskAFileAlreadyCreatedStillTakesEverySave) {
    test::Tmpfs disk(256 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << disk.error();
    const auto path = disk.path() + "/sp.image";
    ImageFile file(path, "sp", fingerprint, length);
    ASSERT_EQ(file.save(image(1)), std::nullopt);
    ASSERT_GT(disk.fill(), 0u);
    // A new file cannot be created any more...
    ImageFile other(disk.path() + "/other.image", "other", fingerprint, length);
    const auto refused = other.save(image(1));
    ASSERT_TRUE(refused.has_value());
    EXPECT_NE(refused->find("No space left on device"), std::string::npos) << *refused;
    // ...but the slots of this one are overwritten in place.
    for (unsigned i = 2; i <= 6; ++i) ASSERT_EQ(file.save(image(i)), std::nullopt) << i;
    EXPECT_EQ(ImageFile(path, "sp", fingerprint, length).loaded(), image(6));
}

TEST_F(ImageFileTest, AFileRemovedOnAFullDiskIsWrittenAgainInTheRoomItLeaves) {
    test::Tmpfs disk(256 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << disk.error();
    const auto path = disk.path() + "/sp.image";
    ImageFile file(path, "sp", fingerprint, length);
    ASSERT_EQ(file.save(image(1)), std::nullopt);
    fs::remove(path);  // its blocks stay taken while the file is open
    ASSERT_GT(disk.fill(), 0u);
    ASSERT_EQ(file.save(image(2)), std::nullopt);
    EXPECT_EQ(ImageFile(path, "sp", fingerprint, length).loaded(), image(2));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::state
