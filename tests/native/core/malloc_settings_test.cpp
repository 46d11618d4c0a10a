// The CLI's allocator settings (core/malloc_settings.hpp), observed through
// glibc's own count of chunks it mapped on their own (mallinfo2().hblks): a
// 40 MiB block is mapped under a 1 MiB threshold and taken from the heap under
// a 64 MiB one.
#include <gtest/gtest.h>

#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "sheetgen/core/malloc_settings.hpp"

namespace sheetgen {

#if defined(__GLIBC__)
namespace {
// Chunks glibc mapped on their own while a block of `bytes` is held.
std::size_t mapped_chunks_holding(std::size_t bytes) {
  static void* volatile held;  // volatile: the compiler may not drop the malloc/free pair
  held = std::malloc(bytes);
  const std::size_t n = mallinfo2().hblks;
  std::free(held);
  return n;
}
}  // namespace
#endif

TEST(MallocSettings, TheMmapThresholdDecidesWhetherALargeBlockIsMappedOnItsOwn) {
#if defined(__GLIBC__)
  if (!malloc_settings_apply()) GTEST_SKIP() << "a sanitizer's malloc: the settings do nothing";
  const std::size_t before = mallinfo2().hblks;
  MallocSettings low;
  low.mmap_threshold_bytes = std::size_t(1) << 20;
  ASSERT_STREQ(apply_malloc_settings(low), "");
  EXPECT_EQ(mapped_chunks_holding(std::size_t(40) << 20), before + 1);
  MallocSettings high;
  high.mmap_threshold_bytes = std::size_t(64) << 20;
  ASSERT_STREQ(apply_malloc_settings(high), "");
  EXPECT_EQ(mapped_chunks_holding(std::size_t(40) << 20), before);
  EXPECT_STREQ(apply_malloc_settings(), "");  // the CLI's
#else
  GTEST_SKIP() << "not glibc: the settings do nothing";
#endif
}

}  // namespace sheetgen
