#pragma once
// Leaf point buckets: each leaf's points lie in one contiguous structure-of-arrays block (x[], y[],
// z[], then one array per kept column: stamps, ids, intensities, times), so a leaf is read front
// to back with no pointer chase. Blocks come in size classes growing by about 1.2-1.33x; each class
// is a pool of fixed-size pages with a free list, so growing a pool never moves or copies what it
// holds. A block begins with the id of the leaf it was last handed to, so that a map that shrank
// can move its blocks down and give the emptied pages back (compact()). The pages are shared with
// snapshots (core/storage/shared_pages.hpp): a block is written through write_block(), which copies a
// page a snapshot holds, or, past its points, through tail_block(), which does not; a block no
// snapshot reads is written where it lies (in_place(); docs/design.md, "Snapshots").

#include "core/storage/blocks_per_page.hpp"
#include "core/storage/mapped_memory.hpp"
#include "core/storage/node_store.hpp"
#include "core/storage/point_types.hpp"
#include "core/storage/shared_pages.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <vector>

namespace eco::detail {

class PointStore {
 public:
  explicit PointStore(Columns columns = {}, std::shared_ptr<PageLedger> ledger = std::make_shared<PageLedger>())
      : columns_(columns), ledger_(std::move(ledger)) {}

  /// A store over the same pages, to be read only (a snapshot's): nothing is copied until this
  /// store writes a page. It has no free lists. Blocks this store lets go of from now on stay
  /// unwritten until the new store is gone (settle()): it may read them.
  [[nodiscard]] PointStore share() {
    PointStore copy(columns_, ledger_);
    copy.pools_.resize(pools_.size());
    Share mark{std::make_shared<std::atomic<bool>>(true), {}};
    for (std::size_t c = 0; c < pools_.size(); ++c) {
      Pool& to = copy.pools_[c];
      Pool& from = pools_[c];
      std::tie(to.block_bytes, to.per_page, to.used) = std::tie(from.block_bytes, from.per_page, from.used);
      to.pages = from.pages.share();
      from.shared = true;
      mark.released_before.push_back(std::uint32_t(from.released.size()));
    }
    copy.held_ = SnapshotHold(mark.alive);
    shares_.push_back(std::move(mark));
    return copy;
  }
  /// Once no snapshot is left: every block let go of is free again.
  void end_sharing() {
    shares_.clear();
    for (std::size_t c = 0; c < pools_.size(); ++c) {
      take_released(c, pools_[c].released.size());
      pools_[c].shared = false;
    }
  }
  /// Lets go of the pages a write copied (core/storage/shared_pages.hpp); returns their bytes.
  std::size_t release_replaced() {
    std::size_t bytes = 0;
    for (Pool& p : pools_) bytes += p.pages.release_replaced();
    return bytes;
  }

  /// Appends [first, last) (StoredPoints, or BarePoints when no column is kept) to the block at
  /// `link` that holds `count` points (kNone: no block yet), of node `owner` (compact() tells it
  /// when its block moves). A block that must grow is made to hold `room` points if that is more
  /// (points known to be on their way).
  template <class Point>
  void append(std::uint32_t& link, std::uint32_t owner, std::uint32_t count, const Point* first, const Point* last,
              std::uint32_t room = 0) {
    const auto m = std::uint32_t(last - first);
    if (m == 0) return;
    reserve(link, owner, count, count + m, room);
    const Block b = tail_block(link);
    // column by column: each loop writes one array, with no test per point
    float* x = b.x + count;
    float* y = x + b.capacity;
    float* z = y + b.capacity;
    for (std::uint32_t i = 0; i < m; ++i) {
      x[i] = first[i].p[0];
      y[i] = first[i].p[1];
      z[i] = first[i].p[2];
    }
    if constexpr (std::is_same_v<Point, StoredPoint>) {
      if (b.stamps) std::transform(first, last, b.stamps + count, [](const StoredPoint& s) { return s.stamp; });
      if (b.ids) std::transform(first, last, b.ids + count, [](const StoredPoint& s) { return s.id; });
      if (b.intensities) std::transform(first, last, b.intensities + count, [](const StoredPoint& s) { return s.intensity; });
      if (b.times) std::transform(first, last, b.times + count, [](const StoredPoint& s) { return s.time; });
    } else {
      static_assert(std::is_same_v<Point, BarePoint>);
      assert(columns_.count() == 0);
    }
  }

  /// Appends the points source[picked[0]], ..., source[picked[n - 1]] (of another block of this
  /// store) to the block at `link`, as append() does.
  void append_picked(std::uint32_t& link, std::uint32_t owner, std::uint32_t count, const PointSpan& source,
                     const std::uint32_t* picked, std::uint32_t n, std::uint32_t room = 0) {
    append_columns(link, owner, count, source, n, room, [&](auto* to, const auto* from) {
      for (std::uint32_t i = 0; i < n; ++i) to[i] = from[picked[i]];
    });
  }
  /// Appends values [first, first + n) of each of `source`'s columns (the columns this store
  /// keeps, and only those) to the block at `link`, as append() does.
  void append_bytes(std::uint32_t& link, std::uint32_t owner, std::uint32_t count, const ColumnBytes& source,
                    std::size_t first, std::uint32_t n) {
    append_columns(link, owner, count, source, n, 0, [&](auto* to, const std::byte* from) {
      static_assert(sizeof(*to) == 4);
      std::memcpy(to, from + first * 4, std::size_t(n) * 4);
    });
  }

  /// Maps at once the pages that fresh blocks for leaves of `counts` points (each, at most one
  /// block's) will fill, rather than a page at a time as blocks are taken (a map loaded).
  void make_room_for(std::span<const std::uint32_t> counts) {
    MappedVector<std::uint32_t> blocks(kClasses, 0);
    for (const std::uint32_t n : counts) {
      if (n > 0) ++blocks[std::size_t(class_for(n))];
    }
    for (std::size_t c = 0; c < kClasses; ++c) {
      if (blocks[c] == 0) continue;
      Pool& p = pool(int(c));
      const std::size_t pages = (std::size_t(p.used) + blocks[c] + p.per_page.count - 1) / p.per_page.count;
      if (pages > p.pages.size()) p.pages.push_back_fresh(pages - p.pages.size());
    }
  }

  /// The `count` points of the block at `link`.
  [[nodiscard]] PointSpan span(std::uint32_t link, std::uint32_t count) const {
    if (link == kNone) return {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, 0};
    const Block b = block(link);
    return {b.x, b.x + b.capacity, b.x + 2 * std::size_t(b.capacity), b.stamps, b.ids, b.intensities, b.times,
            count};
  }

  /// Calls f(const StoredPoint&) for each of the `count` points at `link`.
  template <class F>
  void for_each(std::uint32_t link, std::uint32_t count, F&& f) const {
    const PointSpan s = span(link, count);
    for (std::uint32_t i = 0; i < s.size; ++i) f(s[i]);
  }

  /// Keeps the points for which keep(const StoredPoint&) holds, in order; returns how many.
  /// A block left far larger than its points moves to a smaller one; an empty one is released.
  template <class Keep>
  std::uint32_t retain(std::uint32_t& link, std::uint32_t count, Keep&& keep) {
    if (link == kNone) return 0;
    const Block from = block(link);
    std::optional<Block> to;  // written from the first point that goes: a block that keeps all stays shared
    std::uint32_t kept = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      const StoredPoint s = read(from, i);
      if (!keep(s)) {
        if (!to) to = write_block(link);
        continue;
      }
      if (to) write(*to, kept, s);
      ++kept;
    }
    if (kept == 0) {
      release(link);
    } else if (class_for(kept) + 1 < class_of(link)) {
      move_to(link, owner_of(link), kept, class_for(kept));  // the same leaf's
    }
    return kept;
  }

  /// Adds `shift` [s] to the times of the `count` points at `link` (rounded once more to float).
  void shift_times(std::uint32_t link, std::uint32_t count, double shift) {
    if (link == kNone || !columns_.times) return;
    float* times = write_block(link).times;
    for (std::uint32_t i = 0; i < count; ++i) times[i] = float(double(times[i]) + shift);
  }

  /// Appends the `count` points at `link` to `out` and releases the block.
  void drain(std::uint32_t& link, std::uint32_t count, std::vector<StoredPoint>& out) {
    for_each(link, count, [&](const StoredPoint& s) { out.push_back(s); });
    release(link);
  }

  void release(std::uint32_t& link) {
    if (link == kNone) return;
    // the owner named in the block is left as it was: compact() asks whether it still holds it
    Pool& p = pools_[std::size_t(class_of(link))];
    (p.shared ? p.released : p.free).push_back(index_of(link));
    link = kNone;
  }

  [[nodiscard]] const Columns& columns() const { return columns_; }
  [[nodiscard]] std::size_t bytes() const {
    std::size_t total = pools_.capacity() * sizeof(Pool);
    for (const Pool& p : pools_) {
      total += p.pages.bytes() + (p.free.capacity() + p.released.capacity()) * sizeof(std::uint32_t);
    }
    return total;
  }

  /// The node the block at `link` (not kNone) was last handed to.
  [[nodiscard]] std::uint32_t owner_of(std::uint32_t link) const {
    std::uint32_t owner;
    std::memcpy(&owner, address(link), sizeof owner);
    return owner;
  }

  /// Bytes of the blocks the pools hold free (compact() gives most of them back).
  [[nodiscard]] std::size_t free_bytes() const {
    std::size_t total = 0;
    for (const Pool& p : pools_) total += (p.free.size() + p.released.size()) * p.block_bytes;
    return total;
  }

  /// Moves the live blocks at the top of each pool into free ones below, from the top down, and
  /// releases the pages emptied behind them, as a map that shrank needs; stops once it has moved
  /// or dropped `budget` bytes of blocks, so that no update pays for all at once (each block read,
  /// each page released costs). holds(owner, link) says whether the node a block was last handed
  /// to still holds it (else the block is free); relink(owner, link) hands each moved block's
  /// owner its new link. Returns the bytes of blocks moved or dropped.
  template <class Holds, class Relink>
  std::size_t compact(std::size_t budget, Holds&& holds, Relink&& relink) {
    std::size_t done = 0;
    settle();
    for (std::size_t c = 0; c < pools_.size(); ++c) {
      Pool& p = pools_[c];
      while (p.used > 0 && done < budget) {
        const std::uint32_t top = p.used - 1;
        const std::uint32_t from_link = std::uint32_t(c) << kIndexBits | top;
        const std::uint32_t owner = owner_of(from_link);
        if (!holds(owner, from_link)) {  // free: dropped where it lies
          --p.used;
          done += p.block_bytes;
          continue;
        }
        while (!p.free.empty() && p.free.back() >= top) p.free.pop_back();  // above the top: gone
        if (p.free.empty()) break;
        const std::uint32_t to = p.free.back();
        p.free.pop_back();
        const std::uint32_t to_link = std::uint32_t(c) << kIndexBits | to;
        std::memcpy(in_place(to_link), address(from_link), p.block_bytes);  // its owner too; a free block: no copy
        relink(owner, to_link);
        --p.used;
        done += p.block_bytes;
      }
      std::erase_if(p.free, [&](std::uint32_t i) { return i >= p.used; });
      drop_released_from(c, p.used);
      const std::size_t pages = (std::size_t(p.used) + p.per_page.count - 1) / p.per_page.count;
      p.pages.resize_down(pages);  // the emptied pages go back
      if (4 * p.free.size() < p.free.capacity()) p.free.shrink_to_fit();
    }
    return done;
  }

  /// Points a block of size class c holds: 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32, ... (steps
  /// of 1.2-1.33x up to 4096, so a leaf's block is ~90 % full on average; then 2x).
  static std::uint32_t capacity_of(int c) { return kCapacities[std::size_t(c)]; }
  /// The smallest size class that holds n points.
  static int class_for(std::uint32_t n) {  // n > 2^31 is refused
    if (n > kCapacities.back()) throw std::length_error("eco: too many points in one leaf");
    int c = 0;
    while (capacity_of(c) < n) ++c;
    return c;
  }

 private:
  static constexpr int kIndexBits = 26;  // a link: size class above, block index below
  // 2, 3, 4, 5, 6, then 8, 10, 12 times each power of two up to 4096 (a leaf at most ~10 % empty
  // on average), then doubling to 2^31 (leaves that large are points stacked at the maximum depth)
  static constexpr std::size_t kClasses = 52;
  static constexpr std::array<std::uint32_t, kClasses> kCapacities = [] {
    std::array<std::uint32_t, kClasses> caps{2, 3, 4, 5, 6};
    for (std::size_t c = 5; c <= 32; ++c) caps[c] = std::uint32_t(8 + 2 * ((c - 5) % 3)) << ((c - 5) / 3);
    for (std::size_t c = 33; c < kClasses; ++c) caps[c] = 2 * caps[c - 1];
    return caps;
  }();
  static_assert(kClasses <= std::size_t{1} << (32 - kIndexBits));

  static constexpr std::uint32_t kIndexMask = (std::uint32_t{1} << kIndexBits) - 1;
  static constexpr std::size_t kPageBytes = kMappedFrom;  // small: a sparse map pays little per size class
  static constexpr std::size_t kMostPageBytes = std::size_t{1} << 14;

  struct Pool {
    std::size_t block_bytes = 0;
    BlocksPerPage per_page;
    PageTable pages;  // of whole pages of the system's
    std::uint32_t used = 0;  // blocks handed out so far, free or not
    MappedVector<std::uint32_t> free;
    // While a snapshot may read the pages: the blocks let go of since the oldest one alive was
    // taken, oldest first; a snapshot may read them, so a take reuses one only where its page
    // is the tree's own again, or last, copying its page. `free` blocks are read by none: a take
    // writes them where they lie, even on a page a snapshot holds (settle()).
    bool shared = false;
    MappedVector<std::uint32_t> released;
  };
  struct Block {
    float* x;
    std::uint32_t* stamps;
    std::uint32_t* ids;
    float* intensities;
    float* times;
    std::uint32_t capacity;
  };

  static int class_of(std::uint32_t link) { return int(link >> kIndexBits); }
  static std::uint32_t index_of(std::uint32_t link) { return link & kIndexMask; }

  /// A block starts with the node it was last handed to (compact() asks it), then its columns.
  static constexpr std::size_t kOwnerBytes = sizeof(std::uint32_t);
  /// Where the block at `link` starts, to read.
  [[nodiscard]] const std::byte* address(std::uint32_t link) const {
    const Pool& p = pools_[std::size_t(class_of(link))];
    const std::uint32_t i = index_of(link);
    const std::uint32_t page = p.per_page.page_of(i);
    return p.pages.read(page) + (i - page * p.per_page.count) * p.block_bytes;
  }
  /// The same to write (its page copied first while a snapshot holds it).
  [[nodiscard]] std::byte* writable(std::uint32_t link) {
    Pool& p = pools_[std::size_t(class_of(link))];
    const std::uint32_t i = index_of(link);
    const std::uint32_t page = p.per_page.page_of(i);
    return p.pages.write(page) + (i - page * p.per_page.count) * p.block_bytes;
  }
  /// The block at `link`, to read only.
  [[nodiscard]] Block block(std::uint32_t link) const {
    return layout(const_cast<std::byte*>(address(link)), class_of(link));  // NOLINT: read only
  }
  /// The block at `link`, to write.
  [[nodiscard]] Block write_block(std::uint32_t link) { return layout(writable(link), class_of(link)); }
  /// The block at `link`, to write past its points only (appending), with no copy of its page: a
  /// snapshot reads a block no further than the points it held then, never more than it holds now
  /// while the page is shared, since every write below them copies the page (write_block) and a
  /// block handed out anew is read by no snapshot (take()).
  [[nodiscard]] Block tail_block(std::uint32_t link) const { return block(link); }
  /// Where the block at `link` starts, to write with no copy of its page: for a block no
  /// snapshot reads (free, or handed out since the oldest snapshot alive was taken).
  [[nodiscard]] std::byte* in_place(std::uint32_t link) const {
    return const_cast<std::byte*>(address(link));  // NOLINT: the page's other blocks are not written
  }
  /// The columns of a block of class c at `start`.
  [[nodiscard]] Block layout(std::byte* start, int c) const {
    std::byte* at = start + kOwnerBytes;
    const std::uint32_t cap = capacity_of(c);
    std::byte* column = at + 3 * sizeof(float) * cap;  // the kept columns follow x, y, z in order
    auto next = [&]<class T>(bool kept, T*) -> T* {
      if (!kept) return nullptr;
      T* out = reinterpret_cast<T*>(column);
      column += sizeof(T) * cap;
      return out;
    };
    Block b{reinterpret_cast<float*>(at), nullptr, nullptr, nullptr, nullptr, cap};
    b.stamps = next(columns_.stamps, b.stamps);
    b.ids = next(columns_.ids, b.ids);
    b.intensities = next(columns_.intensities, b.intensities);
    b.times = next(columns_.times, b.times);
    return b;
  }
  /// append_picked's and append_bytes's common part: makes room for `n` more points and calls
  /// copy(to, from) for each column `source` (a PointSpan or ColumnBytes) has, `to` the block's
  /// column past its `count` points.
  template <class Source, class Copy>
  void append_columns(std::uint32_t& link, std::uint32_t owner, std::uint32_t count, const Source& source,
                      std::uint32_t n, std::uint32_t room, Copy&& copy) {
    if (n == 0) return;
    reserve(link, owner, count, count + n, room);
    const Block b = tail_block(link);
    const auto column = [&](auto* to, const auto* from) {
      if (from != nullptr) copy(to + count, from);  // null: a column not kept
    };
    column(b.x, source.x);
    column(b.x + b.capacity, source.y);
    column(b.x + 2 * std::size_t(b.capacity), source.z);
    column(b.stamps, source.stamps);
    column(b.ids, source.ids);
    column(b.intensities, source.intensities);
    column(b.times, source.times);
  }
  static StoredPoint read(const Block& b, std::uint32_t i) {
    return {{b.x[i], b.x[b.capacity + i], b.x[2 * std::size_t(b.capacity) + i]},
            b.stamps ? b.stamps[i] : 0u,
            b.ids ? b.ids[i] : 0u,
            b.intensities ? b.intensities[i] : 0.0f,
            b.times ? b.times[i] : 0.0f};
  }
  static void write(Block& b, std::uint32_t i, const StoredPoint& s) {
    b.x[i] = s.p[0];
    b.x[b.capacity + i] = s.p[1];
    b.x[2 * std::size_t(b.capacity) + i] = s.p[2];
    if (b.stamps) b.stamps[i] = s.stamp;
    if (b.ids) b.ids[i] = s.id;
    if (b.intensities) b.intensities[i] = s.intensity;
    if (b.times) b.times[i] = s.time;
  }

  /// Makes the block at `link` (holding `count`, of node `owner`) hold at least `needed` points;
  /// a block that must move for them is made to hold `room` if that is more.
  void reserve(std::uint32_t& link, std::uint32_t owner, std::uint32_t count, std::uint32_t needed, std::uint32_t room) {
    assert(link == kNone || owner_of(link) == owner);
    if (link != kNone && capacity_of(class_of(link)) >= needed) return;
    move_to(link, owner, count, class_for(std::max(needed, room)));
  }
  /// Moves the `count` points at `link` (of node `owner`) to a fresh block of class c.
  void move_to(std::uint32_t& link, std::uint32_t owner, std::uint32_t count, int c) {
    const std::uint32_t fresh = take(c, owner);
    if (link != kNone) {
      copy_points(block(link), tail_block(fresh), count);
      release(link);
    }
    link = fresh;
  }
  /// Copies the first `count` points of `from` into `to`, one column at a time.
  static void copy_points(const Block& from, const Block& to, std::uint32_t count) {
    for (std::size_t a = 0; a < 3; ++a) std::copy_n(from.x + a * from.capacity, count, to.x + a * to.capacity);
    if (from.stamps) std::copy_n(from.stamps, count, to.stamps);
    if (from.ids) std::copy_n(from.ids, count, to.ids);
    if (from.intensities) std::copy_n(from.intensities, count, to.intensities);
    if (from.times) std::copy_n(from.times, count, to.times);
  }
  /// The pool of size class c, set up on first use.
  Pool& pool(int c) {
    if (pools_.size() <= std::size_t(c)) pools_.resize(std::size_t(c) + 1);
    Pool& p = pools_[std::size_t(c)];
    if (p.block_bytes == 0) {
      p.block_bytes = kOwnerBytes + std::size_t(capacity_of(c)) * std::size_t(3 + columns_.count()) * sizeof(float);
      // a page is mapped in whole pages of the system's (core/storage/mapped_memory.hpp): the
      // fewest of them that hold at least one block with at most an eighth left over, or
      // kMostPageBytes; a sparse pool pays for one such page, not for a page of 2^k blocks
      const auto left_over = [&](std::size_t page) { return (page - kPageHeaderBytes) % p.block_bytes; };
      std::size_t page = (kPageHeaderBytes + p.block_bytes + kPageBytes - 1) / kPageBytes * kPageBytes;
      while (8 * left_over(page) > page && page < kMostPageBytes) page += kPageBytes;
      p.per_page = BlocksPerPage(std::uint32_t((page - kPageHeaderBytes) / p.block_bytes));
      p.pages = PageTable(page, ledger_);
    }
    return p;
  }
  std::uint32_t take(int c, std::uint32_t owner) {
    Pool& p = pool(c);
    if (p.free.empty() && !p.released.empty()) settle();
    std::uint32_t i;
    bool copy_page = false;  // a block a snapshot may read, on a page it holds
    if (!p.released.empty() && !p.pages.copies_on_write(p.per_page.page_of(p.released.back()))) {
      i = pop_released(std::size_t(c));
    } else if (!p.free.empty()) {
      i = p.free.back();
      p.free.pop_back();
    } else if (2 * p.released.size() > p.used) {  // a snapshot held long: its copies are bounded, fresh blocks not
      i = pop_released(std::size_t(c));
      copy_page = true;
    } else {
      if (p.used > kIndexMask) throw std::length_error("eco: too many point blocks of one size");
      if (p.per_page.page_of(p.used) == p.pages.size()) p.pages.push_back();
      i = p.used++;
      copy_page = true;  // a block a compaction moved from may lie here, on a page a snapshot holds
    }
    const std::uint32_t link = std::uint32_t(c) << kIndexBits | i;
    // in the block's first line, written next anyway; from here on no snapshot reads the block
    std::memcpy(copy_page ? writable(link) : in_place(link), &owner, sizeof owner);
    return link;
  }

  /// Frees the first `n` released blocks of pool c (the oldest).
  void take_released(std::size_t c, std::size_t n) {
    Pool& p = pools_[c];
    assert(n <= p.released.size());
    const auto first = p.released.begin(), last = first + std::ptrdiff_t(n);
    p.free.insert(p.free.end(), first, last);
    p.released.erase(first, last);
    for (Share& s : shares_) {
      if (c < s.released_before.size()) s.released_before[c] -= std::min(s.released_before[c], std::uint32_t(n));
    }
  }
  /// Takes the block pool c released last; no snapshot's count of those released before it
  /// is left past the blocks still released.
  std::uint32_t pop_released(std::size_t c) {
    MappedVector<std::uint32_t>& released = pools_[c].released;
    const std::uint32_t i = released.back();
    released.pop_back();
    for (Share& s : shares_) {
      if (c < s.released_before.size()) s.released_before[c] = std::min(s.released_before[c], std::uint32_t(released.size()));
    }
    return i;
  }
  /// Frees the blocks let go of before the oldest snapshot still alive was taken: none reads them.
  /// Runs when a pool has no free block and a snapshot has gone since.
  void settle() {
    // acquire: the gone snapshot's reads finished before the blocks it read are written
    const auto gone = [](const Share& s) { return !s.alive->load(std::memory_order_acquire); };
    if (std::none_of(shares_.begin(), shares_.end(), gone)) return;
    std::erase_if(shares_, gone);
    if (shares_.empty()) return end_sharing();
    const MappedVector<std::uint32_t>& oldest = shares_.front().released_before;
    for (std::size_t c = 0; c < pools_.size(); ++c) take_released(c, c < oldest.size() ? oldest[c] : 0);
  }
  /// Forgets the released blocks of pool c from block `used` on (a compaction dropped them), each
  /// snapshot's count of those released before it less the ones it had.
  void drop_released_from(std::size_t c, std::uint32_t used) {
    MappedVector<std::uint32_t>& released = pools_[c].released;
    const auto below = [&](std::uint32_t n) {
      return std::uint32_t(std::count_if(released.begin(), released.begin() + n, [&](std::uint32_t i) { return i < used; }));
    };
    for (Share& s : shares_) {
      if (c < s.released_before.size()) s.released_before[c] = below(s.released_before[c]);
    }
    std::erase_if(released, [&](std::uint32_t i) { return i >= used; });
  }

  /// A snapshot taken of this store: alive while its store is (SnapshotHold), and how many blocks
  /// each pool had released then (those it cannot read).
  struct Share {
    std::shared_ptr<std::atomic<bool>> alive;
    MappedVector<std::uint32_t> released_before;
  };
  /// A snapshot's store's hold on its Share: marks it gone when the store is.
  class SnapshotHold {
   public:
    SnapshotHold() = default;
    explicit SnapshotHold(std::shared_ptr<std::atomic<bool>> alive) : alive_(std::move(alive)) {}
    SnapshotHold(SnapshotHold&& other) noexcept = default;
    SnapshotHold& operator=(SnapshotHold&& other) noexcept {
      std::swap(alive_, other.alive_);
      return *this;
    }
    SnapshotHold(const SnapshotHold&) = delete;
    SnapshotHold& operator=(const SnapshotHold&) = delete;
    ~SnapshotHold() {
      if (alive_) alive_->store(false, std::memory_order_release);
    }

   private:
    std::shared_ptr<std::atomic<bool>> alive_;
  };

  Columns columns_;
  std::shared_ptr<PageLedger> ledger_;
  MappedVector<Pool> pools_;
  MappedVector<Share> shares_;  // the snapshots taken of this store that may be alive, oldest first
  SnapshotHold held_;  // a snapshot's store: its mark
};

}  // namespace eco::detail
