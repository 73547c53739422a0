#include "eip2mqtt/adapters/state/image_store.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::adapters::state {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using core::plan::TagType;

/// A fresh directory under the system's temporary directory, removed afterwards.
class ImageStoreTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() / ("eip2mqtt_image_store_" + std::string(info->name()) +
                                             "_" + std::to_string(::getpid()));
        fs::remove_all(root_);
        dir_ = (root_ / "state").string();
        fs::create_directories(dir_);  // the gateway's StateDirLock makes it
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(root_, ignored);
    }

    fs::path root_;
    std::string dir_;
};

core::plan::ExchangePlan make_plan(std::string name = "setpoints") {
    core::plan::ExchangeSpec spec;
    spec.name = std::move(name);
    spec.direction = core::plan::Direction::produce;
    spec.exchange_id = 10;
    spec.destination = "127.0.0.1";
    spec.topic = "setpoints";
    core::plan::TagSpec speed;
    speed.name = "SPEED_SP";
    speed.address = {0, 0};
    speed.type = TagType::real;
    speed.writable = true;
    speed.mutable_extras().max = 4000;
    core::plan::TagSpec start;
    start.name = "START";
    start.address = {4, 0};
    start.type = TagType::bit;
    start.writable = true;
    spec.tags = {speed, start};
    return core::plan::make_exchange_plan(spec, "acme");
}

std::vector<std::byte> image(std::size_t size, unsigned seed = 1) {
    std::vector<std::byte> bytes(size);
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::byte>(i * 7 + seed);
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

/// Saves through a file opened for the occasion, as a restarted gateway would; true on success.
bool save(const ImageStore& store, const core::plan::ExchangePlan& plan,
          const std::vector<std::byte>& data) {
    const auto error = store.open(plan)->save(data);
    EXPECT_FALSE(error.has_value()) << *error;
    return !error;
}

TEST_F(ImageStoreTest, RoundTrip) {
    const auto plan = make_plan();
    ASSERT_EQ(plan.length, 5u);
    const ImageStore store(dir_);
    EXPECT_FALSE(store.load(plan));  // nothing saved yet
    const auto data = image(plan.length);
    ASSERT_TRUE(save(store, plan, data));
    const auto loaded = store.load(plan);
    ASSERT_TRUE(loaded);
    EXPECT_EQ(*loaded, data);

    // A second save replaces the first.
    const auto newer = image(plan.length, 99);
    ASSERT_TRUE(save(store, plan, newer));
    EXPECT_EQ(store.load(plan).value(), newer);
}

TEST_F(ImageStoreTest, OneFileOfTwoSlotsPerExchange) {
    const auto plan = make_plan();
    const ImageStore store(dir_);
    EXPECT_EQ(store.path_of(plan), dir_ + "/setpoints.image");
    ASSERT_TRUE(save(store, plan, image(plan.length)));
    EXPECT_TRUE(fs::is_regular_file(store.path_of(plan)));
    EXPECT_EQ(fs::file_size(store.path_of(plan)), 8192u);
}

TEST_F(ImageStoreTest, SavesLeaveNoTemporaryFiles) {
    const auto a = make_plan("a");
    const auto b = make_plan("b");
    const ImageStore store(dir_);
    for (unsigned i = 0; i < 5; ++i) {
        ASSERT_TRUE(save(store, a, image(a.length, i)));
        ASSERT_TRUE(save(store, b, image(b.length, i)));
    }
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"a.image", "b.image"}));
}

TEST_F(ImageStoreTest, LayoutChangeIgnored) {
    const ImageStore store(dir_);
    auto plan = make_plan();
    ASSERT_TRUE(save(store, plan, image(plan.length)));

    // A moved tag changes what the bytes mean.
    auto moved = plan;
    moved.tags[1].spec.address = {4, 1};
    EXPECT_NE(layout_fingerprint(moved), layout_fingerprint(plan));
    EXPECT_FALSE(store.load(moved));

    // So does a changed type, or a changed length.
    auto retyped = plan;
    retyped.tags[0].spec.type = TagType::dint;
    EXPECT_FALSE(store.load(retyped));
    auto longer = plan;
    longer.length = 8;
    EXPECT_FALSE(store.load(longer));

    // Renames and limits do not: the image is kept.
    auto renamed = plan;
    renamed.tags[0].spec.name = "SPEED_SETPOINT";
    renamed.tags[0].spec.mutable_extras().max = 3600;
    renamed.tags[0].spec.writable = false;
    EXPECT_EQ(layout_fingerprint(renamed), layout_fingerprint(plan));
    EXPECT_TRUE(store.load(renamed));
}

TEST_F(ImageStoreTest, CorruptFileIgnored) {
    const ImageStore store(dir_);
    const auto plan = make_plan();
    ASSERT_TRUE(save(store, plan, image(plan.length)));
    const auto path = store.path_of(plan);
    const auto good = read_all(path);
    ASSERT_EQ(good.size(), 8192u);

    auto flipped = good;
    flipped[44] = static_cast<char>(flipped[44] ^ 0x01);  // the first data byte of slot 0
    write_all(path, flipped);
    EXPECT_FALSE(store.load(plan));

    auto bad_magic = good;
    bad_magic[0] = 'X';
    write_all(path, bad_magic);
    EXPECT_FALSE(store.load(plan));

    auto other_version = good;
    other_version[12] = 9;  // format version, little-endian
    write_all(path, other_version);
    EXPECT_FALSE(store.load(plan));

    write_all(path, std::vector<char>(100000, 'x'));
    EXPECT_FALSE(store.load(plan));

    write_all(path, good);
    EXPECT_TRUE(store.load(plan));
}

TEST_F(ImageStoreTest, TruncatedFileIgnoredUntilItsFirstSlotIsWhole) {
    const ImageStore store(dir_);
    const auto plan = make_plan();
    ASSERT_TRUE(save(store, plan, image(plan.length)));
    const auto path = store.path_of(plan);
    const auto good = read_all(path);
    for (std::size_t size = 0; size < good.size(); size += size < 64 ? 1 : 509) {
        write_all(path, std::vector<char>(good.begin(), good.begin() + static_cast<long>(size)));
        const auto file = store.open(plan);
        // Slot 0 holds the image; cut short, the file is written whole again by the next save.
        EXPECT_EQ(file->loaded().has_value(), size >= 4096) << "truncated to " << size;
        EXPECT_FALSE(file->in_place()) << "truncated to " << size;
    }
}

TEST_F(ImageStoreTest, PathSeparatorsStayInTheDirectory) {
    const ImageStore store(dir_);
    const auto plan = make_plan("../evil/name");
    EXPECT_EQ(store.path_of(plan), dir_ + "/.._evil_name.image");
    ASSERT_TRUE(save(store, plan, image(plan.length)));
    EXPECT_TRUE(fs::exists(dir_ + "/.._evil_name.image"));
    EXPECT_TRUE(store.load(plan));
}

TEST_F(ImageStoreTest, SaveFailsNamingTheFileWhenTheDirectoryIsMissing) {
    const ImageStore store((root_ / "missing").string());
    const auto plan = make_plan();
    const auto error = store.open(plan)->save(image(plan.length));
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(*error, "open " + (root_ / "missing" / "setpoints.image.tmp").string() +
                          ": No such file or directory");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::state
