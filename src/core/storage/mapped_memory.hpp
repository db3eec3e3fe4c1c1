#pragma once
// The tree's larger memory is mapped for it alone, not taken from the process's heap.
//
// A map updated between its caller's own per-frame allocations would otherwise put its blocks and
// buffers into the free space the caller reuses each frame: the caller's next large allocations
// no longer fit there, go to the heap's top, and are handed back to the kernel when freed, so
// every frame faults fresh pages in the caller's code (examples/eco_caller_faults shows it).
// Memory of the tree's own leaves the caller's heap as if the map were not there.
//
// Allocations under a page still come from the heap (a page each would waste most of it), and so
// does everything under AddressSanitizer, which checks heap memory only.

#include <cstddef>
#include <utility>
#include <vector>

namespace eco::detail {

/// Bytes from which an allocation is mapped rather than taken from the heap: one page.
inline constexpr std::size_t kMappedFrom = std::size_t{1} << 12;

/// Whether allocations from kMappedFrom on are mapped (not under AddressSanitizer).
[[nodiscard]] bool allocations_are_mapped();

/// Whether allocate_bytes(bytes) hands out zeroed memory (a fresh mapping's).
[[nodiscard]] bool comes_zeroed(std::size_t bytes);
/// `bytes` (> 0) of memory: mapped pages from kMappedFrom on, else the heap's. Throws
/// std::bad_alloc when there is none.
[[nodiscard]] void* allocate_bytes(std::size_t bytes);
/// The same for memory about to be written whole (a pool's page): a mapping is faulted in by the
/// call itself, at once, rather than a 4 KiB page at a time as it is first written.
[[nodiscard]] void* allocate_written_bytes(std::size_t bytes);
/// `count` blocks of `bytes` each (a multiple of kMappedFrom), about to be written whole: mapped,
/// one mapping faulted in at once, handed to `take(void*)` a block at a time; each block is given
/// back on its own (release_bytes(block, bytes)), as if it had been allocated alone.
template <class Take>
void allocate_written_blocks(std::size_t bytes, std::size_t count, Take&& take);
/// Gives back what allocate_bytes(bytes) or allocate_written_bytes(bytes) returned.
void release_bytes(void* memory, std::size_t bytes) noexcept;

/// One mapping of `bytes` faulted in at once (allocate_written_blocks), or null where allocations
/// are not mapped (then each block is allocated alone).
[[nodiscard]] std::byte* map_written(std::size_t bytes);

template <class Take>
void allocate_written_blocks(std::size_t bytes, std::size_t count, Take&& take) {
  if (count == 0) return;
  std::byte* run = bytes % kMappedFrom == 0 ? map_written(bytes * count) : nullptr;
  for (std::size_t i = 0; i < count; ++i) take(run ? run + i * bytes : allocate_written_bytes(bytes));
}

/// A standard allocator over allocate_bytes: for the containers the tree keeps.
template <class T>
struct MappedAllocator {
  using value_type = T;
  MappedAllocator() = default;
  template <class U>
  MappedAllocator(const MappedAllocator<U>&) noexcept {}  // NOLINT: converts as std::allocator does
  [[nodiscard]] T* allocate(std::size_t n) { return static_cast<T*>(allocate_bytes(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { release_bytes(p, n * sizeof(T)); }
  friend bool operator==(MappedAllocator, MappedAllocator) noexcept { return true; }
};

/// `bytes` from allocate_bytes, owned: given back when it goes.
class MappedPage {
 public:
  explicit MappedPage(std::size_t bytes) : memory_(static_cast<std::byte*>(allocate_bytes(bytes))), bytes_(bytes) {}
  MappedPage(MappedPage&& other) noexcept
      : memory_(std::exchange(other.memory_, nullptr)), bytes_(other.bytes_) {}
  MappedPage& operator=(MappedPage&& other) noexcept {
    std::swap(memory_, other.memory_);
    std::swap(bytes_, other.bytes_);
    return *this;
  }
  ~MappedPage() { release_bytes(memory_, bytes_); }
  [[nodiscard]] std::byte* get() const { return memory_; }

 private:
  std::byte* memory_;
  std::size_t bytes_;
};

/// A vector whose storage is the tree's own (mapped once it reaches a page).
template <class T>
using MappedVector = std::vector<T, MappedAllocator<T>>;

}  // namespace eco::detail
