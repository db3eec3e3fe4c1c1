#pragma once
// Points per world-grid cell, kept as points come and go, so that the density cap's question
// "how many points does this cell hold?" is one hash lookup instead of a walk of the tree.
//
// Every held point lies in the ego box, whose side spans fewer than 2^18 cells (Config::validate
// checks it), so a cell is named without ambiguity by its grid indices modulo 2^18: three 18-bit
// fields. A slot is one 64-bit word — the cell's key in the high 54 bits, its count in the low 10
// (so at most 1023 points per cell) — in an open-addressing table with linear probing and
// backward-shift deletion (no tombstones).

#include "core/set_flags.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace eco::detail {

class CellCounts {
 public:
  /// Keys add_below_each judges together.
  static constexpr std::size_t kMaxKeys = 64;  // the open ones are one word's bits
  static constexpr int kAxisBits = 18;
  static constexpr std::uint32_t kMaxCount = (1u << 10) - 1;

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

  /// Starts loading the slots where the probes of keys[0, n) begin (a hint: no effect on the
  /// counts); the table's address and shift read once, not once a key.
  void prefetch_each(const std::uint64_t* keys, std::size_t n) const {
    if (slots_.empty()) return;
    const std::uint64_t* const slots = slots_.data();
    const int shift = shift_;
    for (std::size_t i = 0; i < n; ++i) __builtin_prefetch(slots + home(keys[i], shift));
  }

  /// Counts one point in `key`'s cell, whatever it holds already.
  void add(std::uint64_t key) { add_below(key, kMaxCount); }

  /// Forgets one point of `key`'s cell; nothing happens if the cell holds none.
  void remove(std::uint64_t key) {
    if (slots_.empty()) return;
    const std::size_t i = find(key);
    if (count_of(slots_[i]) == 0) return;
    if (--slots_[i] & kCountMask) return;
    erase_at(i);
  }

  /// Points counted in `key`'s cell.
  [[nodiscard]] std::uint32_t count(std::uint64_t key) const {
    return slots_.empty() ? 0 : count_of(slots_[find(key)]);
  }

  void clear() {
    std::fill(slots_.begin(), slots_.end(), 0);
    used_ = 0;
  }

  /// Calls f(key, count) for every cell holding a point.
  template <class F>
  void for_each(F&& f) const {
    for (std::uint64_t s : slots_) {
      if (count_of(s) != 0) f(key_of(s), count_of(s));
    }
  }

  [[nodiscard]] std::size_t cells() const { return used_; }
  [[nodiscard]] std::size_t bytes() const { return slots_.capacity() * sizeof(std::uint64_t); }

 private:
  static constexpr int kCountBits = 10;

  /// add_below_each for n <= kMaxKeys keys. Room for n new cells is made first, so the loop tests
  /// no load per key. A cell full when the keys arrive stays full through them (none is emptied
  /// here): the keys found full at or next to their home, or whose cell their predecessors fill,
  /// are refused in vector code, the others probed one by one.
  std::size_t add_below_some(const std::uint64_t* keys, std::size_t n, std::uint32_t limit, std::uint8_t* passed) {
    assert(n <= kMaxKeys);
    while (4 * (used_ + n) > 3 * slots_.size()) grow();
    std::uint64_t* const slots = slots_.data();
    const std::size_t last = slots_.size() - 1;
    std::size_t used = used_, taken = 0;
    for (std::uint64_t open = refuse_full_near_home(slots, last, shift_, keys, n, limit, passed); open != 0;
         open &= open - 1) {
      const auto k = std::size_t(std::countr_zero(open));
      const std::uint64_t key = keys[k];
      const std::size_t i = probe(slots, last, home(key), key);
      const std::uint32_t count = count_of(slots[i]);
      const bool counted = count < limit;
      passed[k] = std::uint8_t(counted);
      taken += counted;
      if (counted) {
        slots[i] = count == 0 ? key << kCountBits | 1u : slots[i] + 1;
        used += count == 0;
      }
    }
    used_ = used;
    return taken;
  }
  /// Sets passed[0, n) = 0 (n <= kMaxKeys); returns the keys[k] left open as bit k: those whose
  /// cell does not hold `limit` points or more in their home slot or the next (of `slots`, size
  /// last + 1), and that do not repeat the key before them (limit 1) or the two before them
  /// (limit 2). (src/core/cell_counts.cpp: vector code; the caller visits only the set bits, a
  /// few of a group's 64 under a cap.)
  static std::uint64_t refuse_full_near_home(const std::uint64_t* slots, std::size_t last, int shift,
                                             const std::uint64_t* keys, std::size_t n, std::uint32_t limit,
                                             std::uint8_t* passed);
  static constexpr std::uint64_t kCountMask = (std::uint64_t{1} << kCountBits) - 1;

  static std::uint64_t key_of(std::uint64_t slot) { return slot >> kCountBits; }
  static std::uint32_t count_of(std::uint64_t slot) { return std::uint32_t(slot & kCountMask); }
  [[nodiscard]] std::size_t home(std::uint64_t key) const { return home(key, shift_); }
  static std::size_t home(std::uint64_t key, int shift) {
    return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift);  // Fibonacci hashing
  }
  [[nodiscard]] std::size_t next(std::size_t i) const { return (i + 1) & (slots_.size() - 1); }
  /// The slot of `key`'s cell, or the empty slot that ends its probe run (the table is not empty).
  [[nodiscard]] std::size_t find(std::uint64_t key) const { return probe(slots_.data(), slots_.size() - 1, home(key), key); }
  /// From slot i of `slots` (size last + 1) on: the slot holding `key`, or the empty slot ending
  /// its probe run. Static, on the caller's copies, so a loop that writes slots keeps them in registers.
  static std::size_t probe(const std::uint64_t* slots, std::size_t last, std::size_t i, std::uint64_t key) {
    while (count_of(slots[i]) != 0 && key_of(slots[i]) != key) i = (i + 1) & last;
    return i;
  }

  void grow() {
    std::vector<std::uint64_t> old(slots_.empty() ? 1024 : 2 * slots_.size(), 0);
    old.swap(slots_);  // slots_ is the bigger, empty table now
    shift_ = 64 - std::countr_zero(slots_.size());
    for (std::uint64_t s : old) {
      if (count_of(s) == 0) continue;
      std::size_t i = home(key_of(s));
      while (count_of(slots_[i]) != 0) i = next(i);
      slots_[i] = s;
    }
  }

  /// Empties slot `hole` and moves later members of its probe run back so no lookup breaks.
  void erase_at(std::size_t hole) {
    slots_[hole] = 0;
    --used_;
    for (std::size_t i = next(hole); count_of(slots_[i]) != 0; i = next(i)) {
      const std::size_t want = home(key_of(slots_[i]));
      // slot i may move to the hole when its home is not in the cyclic range (hole, i]
      const bool stays = hole <= i ? (hole < want && want <= i) : (hole < want || want <= i);
      if (stays) continue;
      slots_[hole] = slots_[i];
      slots_[i] = 0;
      hole = i;
    }
  }

  std::vector<std::uint64_t> slots_;
  std::size_t used_ = 0;
  int shift_ = 64;
};

}  // namespace eco::detail
