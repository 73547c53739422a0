#include "app/detail/release_heap.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <string>

#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

// The sanitizers bring an allocator of their own: glibc's thresholds do not apply there.
#if defined(__SANITIZE_ADDRESS__)
#define EIP2MQTT_GLIBC_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define EIP2MQTT_GLIBC_MALLOC 0
#endif
#endif
#if !defined(EIP2MQTT_GLIBC_MALLOC) && defined(__GLIBC__)
#define EIP2MQTT_GLIBC_MALLOC 1
#endif

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

#if EIP2MQTT_GLIBC_MALLOC
/// Allocates and touches `bytes`, in a way the compiler cannot drop as unused.
void* allocate(std::size_t bytes) {
    void* block = std::malloc(bytes);
    static_cast<volatile char*>(block)[0] = 1;
    asm volatile("" : : "r"(block) : "memory");
    return block;
}

/// Blocks glibc's malloc has mapped on their own, outside its arenas.
std::size_t mapped_blocks() { return ::mallinfo2().hblks; }
#endif

TEST(KeepHeapThresholdsTest, AFreedLargeBlockDoesNotMoveTheNextMidSizedOneIntoTheHeap) {
#if EIP2MQTT_GLIBC_MALLOC
    // On a fresh heap: a free chunk left in it by the tests before would serve the 256 KiB
    // block whatever the thresholds, so the test runs again in a process of its own.
    if (std::getenv("EIP2MQTT_FRESH_HEAP") == nullptr) {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        const std::string command = "EIP2MQTT_FRESH_HEAP=1 /proc/" + std::to_string(::getpid()) +
                                    "/exe --gtest_filter=" + test->test_suite_name() + "." +
                                    test->name() + " >/dev/null 2>&1";
        EXPECT_EQ(std::system(command.c_str()), 0) << command;
        return;
    }
    keep_heap_thresholds();
    // Left dynamic, freeing this mapped 8 MiB block would raise the mmap threshold to 8 MiB,
    // and the 256 KiB block after it would come from the heap, where its pages stay resident
    // once freed.
    std::free(allocate(8u << 20));
    const auto before = mapped_blocks();
    void* mid = allocate(256u << 10);
    EXPECT_EQ(mapped_blocks(), before + 1);
    std::free(mid);
    EXPECT_EQ(mapped_blocks(), before);
#else
    GTEST_SKIP() << "glibc's own malloc only";
#endif
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
