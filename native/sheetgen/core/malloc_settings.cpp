#include "sheetgen/core/malloc_settings.hpp"

// Under AddressSanitizer malloc is the sanitizer's, which ignores mallopt.
#if defined(__SANITIZE_ADDRESS__)
#define SHEETGEN_GLIBC_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHEETGEN_GLIBC_MALLOC 0
#endif
#endif
#if !defined(SHEETGEN_GLIBC_MALLOC) && defined(__GLIBC__)
#define SHEETGEN_GLIBC_MALLOC 1
#elif !defined(SHEETGEN_GLIBC_MALLOC)
#define SHEETGEN_GLIBC_MALLOC 0
#endif

#if SHEETGEN_GLIBC_MALLOC
#include <malloc.h>
#endif

namespace sheetgen {

bool malloc_settings_apply() { return SHEETGEN_GLIBC_MALLOC; }

const char* apply_malloc_settings(const MallocSettings& s) {
#if SHEETGEN_GLIBC_MALLOC
  // The mmap threshold first: setting the trim threshold alone would also fix
  // the mmap threshold, at its 128 KiB default, and map every buffer.
  if (mallopt(M_MMAP_THRESHOLD, static_cast<int>(s.mmap_threshold_bytes)) != 1) return "M_MMAP_THRESHOLD";
  if (mallopt(M_TRIM_THRESHOLD, static_cast<int>(s.trim_threshold_bytes)) != 1) return "M_TRIM_THRESHOLD";
#else
  (void)s;
#endif
  return "";
}

}  // namespace sheetgen
