#pragma once
// Points per world-grid cell, kept as points come and go, so that the density cap's question
// "how many points does this cell hold?" is one hash lookup instead of a walk of the tree.
//
// Every held point lies in the ego box, whose side spans fewer than 2^18 cells (Config::validate
// checks it), so a cell is named without ambiguity by its grid indices modulo 2^18: three 18-bit
// fields, its key. Cells are counted in blocks of 4 x 4 x 4 neighbours: a block is one slot of an
// open-addressing table (linear probing, backward-shift deletion, no tombstones), a tag word (the
// block's key) and its 64 counts of `width` bits each, the fewest bits that hold the cap (1 bit at
// cap 1, 2 at caps 2 and 3, ...). A scan's neighbouring points share a block, so the table is a
// few bytes a held point (an 8-byte slot a cell was 8-16) and mostly stays in cache. A count that
// outgrows its bits (only when a caller counts past the cap: points re-expressed after the
// precision origin moved may cross a wall) keeps the excess in a side table.

#include "core/storage/mapped_memory.hpp"
#include "core/geometry/set_flags.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace eco::detail {

class CellCounts {
 public:
  /// Keys add_below_each judges together.
  static constexpr std::size_t kMaxKeys = 64;  // the open ones are one word's bits
  static constexpr int kAxisBits = 18;
  /// The most points a cell's count holds (add() counts no further).
  static constexpr std::uint32_t kMaxCount = (1u << 10) - 1;

  /// Counts whose bits hold `cap` (a capped add's limit; more is counted in the side table).
  explicit CellCounts(std::uint32_t cap = 1) : width_(width_for(cap)), stride_(1 + std::size_t(width_)) {}

  /// The key of the cell with grid indices g (wrapped modulo 2^18 per axis).
  [[nodiscard]] static std::uint64_t key(const std::array<std::int64_t, 3>& g) {
    constexpr std::uint64_t mask = (std::uint64_t{1} << kAxisBits) - 1;
    return (std::uint64_t(g[0]) & mask) | (std::uint64_t(g[1]) & mask) << kAxisBits |
           (std::uint64_t(g[2]) & mask) << (2 * kAxisBits);
  }

  /// Counts one more point in `key`'s cell if it holds fewer than `limit`; says whether it did.
  bool add_below(std::uint64_t key, std::uint32_t limit) {
    std::uint8_t passed = 0;
    add_below_each(&key, 1, limit, &passed);
    return passed != 0;
  }

  /// add_below(keys[i], limit) for i in [0, n), in order; passed[i] says whether it counted.
  /// Returns how many it counted.
  std::size_t add_below_each(const std::uint64_t* keys, std::size_t n, std::uint32_t limit, std::uint8_t* passed) {
    std::size_t counted = 0;
    for (std::size_t from = 0; from < n; from += kMaxKeys) {
      counted += add_below_some(keys + from, std::min(kMaxKeys, n - from), limit, passed + from);
    }
    return counted;
  }

  /// Counts one point in `key`'s cell, whatever it holds already (up to kMaxCount).
  void add(std::uint64_t key) { add_below(key, kMaxCount); }

  /// Forgets one point of `key`'s cell; nothing happens if the cell holds none.
  void remove(std::uint64_t key) {
    if (slots_.empty()) return;
    const std::size_t slot = find(block_of(key));
    if (!occupied(slot)) return;
    const Place at = place_of(key);
    const std::uint32_t held = bits(slot, at);
    if (held == 0) return;
    if (held == full_bits() && take_extra(key)) return;
    word(slot, at) -= std::uint64_t{1} << at.shift;
    if (held > 1) return;
    --cells_;
    const std::uint64_t* const words = slot_at(slot);
    if (std::all_of(words + 1, words + stride_, [](std::uint64_t w) { return w == 0; })) erase_at(slot);
  }

  /// Points counted in `key`'s cell.
  [[nodiscard]] std::uint32_t count(std::uint64_t key) const {
    if (slots_.empty()) return 0;
    const std::size_t slot = find(block_of(key));
    return occupied(slot) ? count_at(slot, key) : 0;
  }

  void clear() {
    std::fill(slots_.begin(), slots_.end(), 0);
    extra_.clear();
    blocks_ = 0;
    cells_ = 0;
  }

  /// Calls f(key, count) for every cell holding a point.
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t slot = 0; slot < capacity(); ++slot) {
      if (!occupied(slot)) continue;
      const std::uint64_t block = slot_at(slot)[0] & ~kOccupied;
      for (std::uint32_t cell = 0; cell < kBlockCells; ++cell) {
        const std::uint64_t key = block | key_of_cell(cell);
        const std::uint32_t n = count_at(slot, key);
        if (n != 0) f(key, n);
      }
    }
  }

  [[nodiscard]] std::size_t cells() const { return cells_; }
  [[nodiscard]] std::size_t bytes() const {
    // the side table's nodes as libstdc++ allocates them: a link, the pair, and the cached hash
    constexpr std::size_t kExtraNode = sizeof(void*) + sizeof(std::pair<std::uint64_t, std::uint32_t>) + sizeof(std::size_t);
    const std::size_t buckets = extra_.bucket_count() > 1 ? extra_.bucket_count() : 0;  // 1: none allocated yet
    return slots_.capacity() * sizeof(std::uint64_t) + buckets * sizeof(void*) + extra_.size() * kExtraNode;
  }

 private:
  static constexpr std::uint32_t kBlockCells = 64;  // 4 x 4 x 4: two bits of each axis
  static constexpr std::uint64_t kOccupied = std::uint64_t{1} << 63;  // in a tag: the slot holds a block
  /// A key with its cell's place in its block cleared: the block's key.
  static constexpr std::uint64_t kBlockMask = ~(std::uint64_t{3} | std::uint64_t{3} << kAxisBits |
                                                std::uint64_t{3} << (2 * kAxisBits));

  static int width_for(std::uint32_t cap) {
    int width = 1;
    while (width < 16 && (std::uint64_t{1} << width) - 1 < cap) width *= 2;
    return width;
  }
  static std::uint64_t block_of(std::uint64_t key) { return key & kBlockMask; }
  /// The cell's place in its block: two bits of each axis, x lowest.
  static std::uint32_t cell_of(std::uint64_t key) {
    return std::uint32_t((key & 3) | ((key >> kAxisBits) & 3) << 2 | ((key >> (2 * kAxisBits)) & 3) << 4);
  }
  static std::uint64_t key_of_cell(std::uint32_t cell) {
    return std::uint64_t(cell & 3) | std::uint64_t((cell >> 2) & 3) << kAxisBits |
           std::uint64_t((cell >> 4) & 3) << (2 * kAxisBits);
  }
  static std::size_t home(std::uint64_t block, int shift) {
    return std::size_t((block * 0x9E3779B97F4A7C15ull) >> shift);  // Fibonacci hashing
  }

  /// Where a cell's count lies in its block's words: word 1 + word_index of the slot, from bit shift.
  struct Place {
    std::uint32_t word_index, shift;
  };
  [[nodiscard]] Place place_of(std::uint64_t key) const {
    const std::uint32_t bit = cell_of(key) * std::uint32_t(width_);
    return {bit >> 6, bit & 63};
  }
  /// A slot's words: its tag (0 when empty), then its block's counts.
  [[nodiscard]] std::uint64_t* slot_at(std::size_t slot) { return slots_.data() + slot * stride_; }
  [[nodiscard]] const std::uint64_t* slot_at(std::size_t slot) const { return slots_.data() + slot * stride_; }
  [[nodiscard]] std::uint64_t& word(std::size_t slot, Place at) { return slot_at(slot)[1 + at.word_index]; }
  [[nodiscard]] std::uint32_t bits(std::size_t slot, Place at) const {
    return std::uint32_t(slot_at(slot)[1 + at.word_index] >> at.shift) & full_bits();
  }
  [[nodiscard]] std::uint32_t full_bits() const { return std::uint32_t((std::uint64_t{1} << width_) - 1); }
  /// The count of `key`'s cell whose bits read `held`: with the side table's excess when they are full.
  [[nodiscard]] std::uint32_t with_extra(std::uint64_t key, std::uint32_t held) const {
    if (held != full_bits()) return held;
    const auto extra = extra_.find(key);
    return held + (extra == extra_.end() ? 0 : extra->second);
  }
  [[nodiscard]] std::uint32_t count_at(std::size_t slot, std::uint64_t key) const {
    return with_extra(key, bits(slot, place_of(key)));
  }
  /// Takes one from the side table's count of `key`; false when it holds none.
  bool take_extra(std::uint64_t key) {
    const auto extra = extra_.find(key);
    if (extra == extra_.end()) return false;
    if (--extra->second == 0) extra_.erase(extra);
    return true;
  }

  /// add_below_each for n <= kMaxKeys keys. Room for n new blocks is made first, so the loop tests
  /// no load per key. A cell full when the keys arrive stays full through them (none is emptied
  /// here): the keys found full in a block at or next to its home, or whose cell their
  /// predecessors fill, are refused in vector code, the others probed one by one.
  std::size_t add_below_some(const std::uint64_t* keys, std::size_t n, std::uint32_t limit, std::uint8_t* passed) {
    assert(n <= kMaxKeys);
    while (4 * (blocks_ + n) > 3 * capacity()) grow();
    std::size_t taken = 0;
    const Table table = view();
    for (std::uint64_t open = refuse_full_near_home(table, keys, n, limit, passed); open != 0; open &= open - 1) {
      const auto k = std::size_t(std::countr_zero(open));
      const std::uint64_t key = keys[k];
      const std::size_t slot = probe(table, home(block_of(key), shift_), block_of(key));
      const Place at = place_of(key);
      const std::uint32_t held = bits(slot, at);  // 0 in an empty slot: all its words are
      const std::uint32_t count = with_extra(key, held);
      const bool counted = count < limit;
      passed[k] = std::uint8_t(counted);
      if (!counted) continue;
      ++taken;
      if (!occupied(slot)) {
        slot_at(slot)[0] = block_of(key) | kOccupied;
        ++blocks_;
      }
      cells_ += count == 0;
      if (held == full_bits()) {
        ++extra_[key];
      } else {
        word(slot, at) += std::uint64_t{1} << at.shift;
      }
    }
    return taken;
  }

  /// The table as the probes read it, copied so that a loop writing slots keeps it in registers.
  struct Table {
    const std::uint64_t* slots;
    std::size_t last;  // slots - 1: a power of two less one
    std::size_t stride;
    int shift;
    int width;
  };
  [[nodiscard]] Table view() const { return {slots_.data(), capacity() - 1, stride_, shift_, width_}; }

  /// Sets passed[0, n) = 0 (n <= kMaxKeys); returns the keys[k] left open as bit k: those whose
  /// cell does not hold `limit` points or more in a block at its home slot or the next, and that
  /// do not repeat the key before them (limit 1) or the two before them (limit 2).
  /// (src/core/density/cell_counts.cpp: vector code; the caller visits only the set bits, a few of a
  /// group's 64 under a cap.)
  static std::uint64_t refuse_full_near_home(const Table& table, const std::uint64_t* keys, std::size_t n,
                                             std::uint32_t limit, std::uint8_t* passed);

  [[nodiscard]] std::size_t capacity() const { return slots_.size() / stride_; }
  [[nodiscard]] bool occupied(std::size_t slot) const { return slot_at(slot)[0] != 0; }
  /// The slot of `block`, or the empty slot that ends its probe run (the table is not empty).
  [[nodiscard]] std::size_t find(std::uint64_t block) const { return probe(view(), home(block, shift_), block); }
  /// From slot i on: the slot holding `block`, or the empty slot ending its probe run.
  static std::size_t probe(const Table& table, std::size_t i, std::uint64_t block) {
    const std::uint64_t tag = block | kOccupied;
    while (table.slots[i * table.stride] != 0 && table.slots[i * table.stride] != tag) i = (i + 1) & table.last;
    return i;
  }

  void grow() {
    const std::size_t slots = slots_.empty() ? 256 : 2 * capacity();
    MappedVector<std::uint64_t> old(slots * stride_, 0);
    old.swap(slots_);  // slots_ is the bigger, empty table now
    shift_ = 64 - std::countr_zero(slots);
    const Table table = view();
    for (std::size_t from = 0; from < old.size(); from += stride_) {
      if (old[from] == 0) continue;
      const std::size_t to = probe(table, home(old[from] & ~kOccupied, shift_), old[from]);
      std::copy_n(&old[from], stride_, slot_at(to));
    }
  }

  /// Empties slot `hole` and moves later members of its probe run back so no lookup breaks.
  void erase_at(std::size_t hole) {
    const std::size_t last = capacity() - 1;
    std::fill_n(slot_at(hole), stride_, 0);
    --blocks_;
    for (std::size_t i = (hole + 1) & last; occupied(i); i = (i + 1) & last) {
      const std::size_t want = home(slot_at(i)[0] & ~kOccupied, shift_);
      // slot i may move to the hole when its home is not in the cyclic range (hole, i]
      const bool stays = hole <= i ? (hole < want && want <= i) : (hole < want || want <= i);
      if (stays) continue;
      std::copy_n(slot_at(i), stride_, slot_at(hole));
      std::fill_n(slot_at(i), stride_, 0);
      hole = i;
    }
  }

  int width_;           // bits a count: 1, 2, 4, 8 or 16
  std::size_t stride_;  // words a slot: the tag, then 64 counts of width_ bits
  MappedVector<std::uint64_t> slots_;
  std::unordered_map<std::uint64_t, std::uint32_t> extra_;  // counts past their bits, by cell key
  std::size_t blocks_ = 0, cells_ = 0;
  int shift_ = 64;
};

}  // namespace eco::detail
