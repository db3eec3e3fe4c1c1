#include "core/storage/mapped_memory.hpp"

#include <sys/mman.h>

#include <new>

namespace eco::detail {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kMaps = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kMaps = false;
#else
constexpr bool kMaps = true;
#endif
#else
constexpr bool kMaps = true;
#endif

bool mapped(std::size_t bytes) { return kMaps && bytes >= kMappedFrom; }

void* map_bytes(std::size_t bytes, int flags) {
  if (!mapped(bytes)) return ::operator new(bytes);
  void* memory = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | flags, -1, 0);
  if (memory == MAP_FAILED) throw std::bad_alloc();
  return memory;
}

}  // namespace

bool allocations_are_mapped() { return kMaps; }

bool comes_zeroed(std::size_t bytes) { return mapped(bytes); }

void* allocate_bytes(std::size_t bytes) { return map_bytes(bytes, 0); }

void* allocate_written_bytes(std::size_t bytes) { return map_bytes(bytes, MAP_POPULATE); }

std::byte* map_written(std::size_t bytes) {
  // a part of a mapping is unmapped as a whole one is: each block goes back on its own
  return mapped(bytes) ? static_cast<std::byte*>(map_bytes(bytes, MAP_POPULATE)) : nullptr;
}

void release_bytes(void* memory, std::size_t bytes) noexcept {
  if (memory == nullptr) return;
  if (!mapped(bytes)) {
    ::operator delete(memory);
    return;
  }
  munmap(memory, bytes);
}

}  // namespace eco::detail
