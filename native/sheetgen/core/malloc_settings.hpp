#pragma once
// How the process's C allocator (glibc malloc) keeps freed memory: set once by
// a program that owns its process (the CLI), before any work.
//
// A solve builds and frees the same large FEM buffers (factors, sparse
// matrices: 10-60 MB each) hundreds of times. glibc's defaults hand such
// buffers back to the kernel on free (chunks above the mmap threshold are
// unmapped; a thread arena's heap whose top is free is trimmed or deleted),
// and the next candidate's FEM takes fresh zeroed pages again: a fifth of a
// bay solve's CPU time was the kernel's. docs/benchmarks.md "Allocator" has
// the measurements behind the values.
#include <cstddef>

namespace sheetgen {

struct MallocSettings {
  // Chunks at least this large are mapped on their own and unmapped on free
  // (glibc's default threshold starts at 128 KiB and follows the largest
  // chunk freed, up to 32 MiB). Setting it also fixes it.
  std::size_t mmap_threshold_bytes = std::size_t(32) << 20;
  // Free memory at the top of a heap is returned to the kernel only beyond
  // this size, and a thread arena's heap is deleted only when more than this
  // is free in it. 128 MiB ran as fast as 1 GiB on the samples with less
  // memory kept (docs/benchmarks.md "Allocator").
  std::size_t trim_threshold_bytes = std::size_t(128) << 20;
};

// Whether the settings act here: glibc's malloc, not a sanitizer's.
bool malloc_settings_apply();

// Applies the settings with mallopt. Returns "" or the setting glibc refused.
// Where they do not act (another C library, AddressSanitizer) it does nothing
// and returns "".
const char* apply_malloc_settings(const MallocSettings& settings = {});

}  // namespace sheetgen
