#include <eco/process_heap.hpp>

#include <climits>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace eco {

bool keep_freed_heap(std::size_t keep_bytes) {
#if defined(__GLIBC__)
  // glibc's largest mapping threshold on 64-bit: 4 Mi * sizeof(long) (DEFAULT_MMAP_THRESHOLD_MAX)
  constexpr int kLargestThreshold = 32 << 20;
  const int keep = keep_bytes > std::size_t(INT_MAX) ? INT_MAX : int(keep_bytes);
  return mallopt(M_MMAP_THRESHOLD, kLargestThreshold) == 1 && mallopt(M_TRIM_THRESHOLD, keep) == 1;
#else
  (void)keep_bytes;
  return false;
#endif
}

}  // namespace eco
