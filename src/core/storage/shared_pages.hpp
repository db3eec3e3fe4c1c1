#pragma once
// Pages that snapshots share with the live tree (copy-on-write).
//
// The tree's point blocks lie in fixed-size pages. Publishing a snapshot takes a reference to
// every page (8 B a page, a 512th of a 4 KiB page's bytes) instead of copying them; the live tree
// then copies a page the first time it writes to it while a snapshot still holds it, and writes
// to its own copy. A snapshot's pages therefore never change, and what an update copies grows
// with what it changed, not with what the map holds. A page its last holder lets go of, on
// whichever thread, is kept spare for the next copies; each update gives back the spare pages
// beyond what it copied itself.

#include "core/storage/mapped_memory.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace eco::detail {

struct PageHeader;

/// The bytes of the pages a tree and its snapshots hold: all of them (spare ones included), and
/// those in the tree's own tables; the difference is what only snapshots keep alive. And the
/// spare pages: let go by every holder, kept for the copies the next update makes, so that
/// publishing every frame does not map and unmap pages every frame (trim_spare() bounds them).
class PageLedger {
 public:
  PageLedger() = default;
  PageLedger(const PageLedger&) = delete;
  PageLedger& operator=(const PageLedger&) = delete;
  ~PageLedger() { trim_spare(0); }

  std::atomic<std::size_t> bytes{0};
  std::atomic<std::size_t> live_bytes{0};
  std::atomic<int> snapshots{0};  // alive
  [[nodiscard]] std::size_t snapshot_bytes() const {
    const std::size_t live = live_bytes.load(std::memory_order_relaxed);
    const std::size_t all = bytes.load(std::memory_order_relaxed);
    return all > live ? all - live : 0;
  }
  /// A spare page of `page_bytes`, or null.
  [[nodiscard]] PageHeader* take_spare(std::size_t page_bytes);
  void keep_spare(PageHeader* page);
  /// Gives the spare pages back to the system but `keep` bytes of them.
  void trim_spare(std::size_t keep);

 private:
  std::mutex mutex_;  // pages are let go on any thread
  struct Spare {  // the spare pages of one size (a table's pages all have one; the pools' differ)
    std::size_t page_bytes = 0;
    MappedVector<PageHeader*> pages;
  };
  std::vector<Spare> spare_;  // a few sizes
  std::size_t spare_bytes_ = 0;
};

/// A page's first bytes: who holds it, how large it is, whose ledger counts it.
struct PageHeader {
  std::atomic<std::uint32_t> holders{1};
  std::uint32_t bytes = 0;  // the whole page, header included
  PageLedger* ledger = nullptr;
};
inline constexpr std::size_t kPageHeaderBytes = 16;
static_assert(sizeof(PageHeader) == kPageHeaderBytes);

/// A table of pages of `page_bytes` each (header included): read in place, written after
/// unshare(). share() hands out a table over the same pages, read-only by contract.
class PageTable {
 public:
  PageTable() = default;
  PageTable(std::size_t page_bytes, std::shared_ptr<PageLedger> ledger);
  PageTable(PageTable&& other) noexcept;
  PageTable& operator=(PageTable&& other) noexcept;
  PageTable(const PageTable&) = delete;
  PageTable& operator=(const PageTable&) = delete;
  ~PageTable();

  [[nodiscard]] std::size_t size() const { return pages_.size(); }
  [[nodiscard]] std::size_t page_bytes() const { return page_bytes_; }
  /// Where page `i`'s items start (past its header), to read.
  [[nodiscard]] const std::byte* read(std::size_t i) const { return items(pages_[i]); }
  /// The same to write: a page a snapshot still holds is first copied (the snapshot keeps its own).
  [[nodiscard]] std::byte* write(std::size_t i) {
    if (shared_[i]) unshare(i);
    return items(pages_[i]);
  }
  /// Whether write(i) would copy page `i` (a snapshot still holds it).
  [[nodiscard]] bool copies_on_write(std::size_t i) const {
    return shared_[i] != 0 && pages_[i]->holders.load(std::memory_order_acquire) > 1;
  }
  /// Appends a fresh, zeroed page.
  void push_back();
  /// Appends `n` fresh, zeroed pages, mapped at once (a map loaded: its pages all come together).
  void push_back_fresh(std::size_t n);
  /// Lets go of the pages from `n` on.
  void resize_down(std::size_t n);
  /// Another table over the same pages, each now held once more; until this table writes a page,
  /// both read the same bytes. The new table must only be read.
  [[nodiscard]] PageTable share();
  /// Lets go of the pages write() replaced by copies, and returns their bytes. They are kept until
  /// then so that what was read from them before the copy stays readable (an update reads a block
  /// while writing others).
  std::size_t release_replaced();
  /// Bytes of the pages this table holds, and of its table.
  [[nodiscard]] std::size_t bytes() const {
    return pages_.size() * page_bytes_ + pages_.capacity() * sizeof(PageHeader*) + shared_.capacity();
  }
  [[nodiscard]] const std::shared_ptr<PageLedger>& ledger() const { return ledger_; }

 private:
  static std::byte* items(PageHeader* page) { return reinterpret_cast<std::byte*>(page) + kPageHeaderBytes; }
  void unshare(std::size_t i);
  void let_go(PageHeader* page) const;

  /// Counts `pages` pages more (or fewer) as the tree's own, if this table is the tree's.
  void count_live(std::ptrdiff_t pages) const;

  std::size_t page_bytes_ = 0;
  bool live_ = true;  // the tree's own table, not a snapshot's
  std::shared_ptr<PageLedger> ledger_;  // outlives every page it counts: each holder of one holds it
  MappedVector<PageHeader*> pages_;
  MappedVector<std::uint8_t> shared_;  // per page: another table may hold it (checked before a write)
  MappedVector<PageHeader*> replaced_;  // held until release_replaced()
};

/// Bytes held for snapshots beside pages (a snapshot's copy of the nodes), counted in a ledger
/// while they are.
class LedgerCharge {
 public:
  LedgerCharge() = default;
  LedgerCharge(std::shared_ptr<PageLedger> ledger, std::size_t bytes) : ledger_(std::move(ledger)), bytes_(bytes) {
    ledger_->bytes.fetch_add(bytes_, std::memory_order_relaxed);
  }
  LedgerCharge(LedgerCharge&& other) noexcept
      : ledger_(std::move(other.ledger_)), bytes_(std::exchange(other.bytes_, 0)) {}
  LedgerCharge& operator=(LedgerCharge&& other) noexcept {
    std::swap(ledger_, other.ledger_);
    std::swap(bytes_, other.bytes_);
    return *this;
  }
  LedgerCharge(const LedgerCharge&) = delete;
  LedgerCharge& operator=(const LedgerCharge&) = delete;
  ~LedgerCharge() {
    if (ledger_) ledger_->bytes.fetch_sub(bytes_, std::memory_order_relaxed);
  }

 private:
  std::shared_ptr<PageLedger> ledger_;
  std::size_t bytes_ = 0;
};

}  // namespace eco::detail
