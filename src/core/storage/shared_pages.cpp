#include "core/storage/shared_pages.hpp"

#include <algorithm>
#include <cstring>
#include <new>
#include <utility>

namespace eco::detail {
namespace {

/// The page at `memory`, a fresh allocation of `bytes`, counted in `ledger`.
PageHeader* start_page(void* memory, std::size_t bytes, PageLedger* ledger) {
  auto* page = new (memory) PageHeader;
  page->bytes = std::uint32_t(bytes);
  page->ledger = ledger;
  ledger->bytes.fetch_add(bytes, std::memory_order_relaxed);
  return page;
}

/// A page of `bytes`: a spare one, or one just mapped, which the system hands out zeroed.
struct NewPage {
  PageHeader* page;
  bool zeroed;
};
NewPage new_page(std::size_t bytes, PageLedger* ledger) {
  if (PageHeader* spare = ledger->take_spare(bytes)) {
    spare->holders.store(1, std::memory_order_relaxed);
    return {spare, false};
  }
  return {start_page(allocate_written_bytes(bytes), bytes, ledger), comes_zeroed(bytes)};
}

}  // namespace

PageTable::PageTable(std::size_t page_bytes, std::shared_ptr<PageLedger> ledger)
    : page_bytes_(page_bytes), ledger_(std::move(ledger)) {}

PageTable::PageTable(PageTable&& other) noexcept
    : page_bytes_(other.page_bytes_),
      live_(other.live_),
      ledger_(std::move(other.ledger_)),
      pages_(std::move(other.pages_)),
      shared_(std::move(other.shared_)),
      replaced_(std::move(other.replaced_)) {
  other.pages_.clear();
  other.shared_.clear();
  other.replaced_.clear();
}

PageTable& PageTable::operator=(PageTable&& other) noexcept {
  if (this == &other) return *this;
  resize_down(0);
  release_replaced();
  page_bytes_ = other.page_bytes_;
  live_ = other.live_;
  ledger_ = std::move(other.ledger_);
  pages_ = std::move(other.pages_);
  shared_ = std::move(other.shared_);
  replaced_ = std::move(other.replaced_);
  other.pages_.clear();
  other.shared_.clear();
  other.replaced_.clear();
  return *this;
}

PageTable::~PageTable() {
  resize_down(0);
  release_replaced();
}

void PageTable::push_back() {
  const auto [page, zeroed] = new_page(page_bytes_, ledger_.get());
  if (!zeroed) std::memset(items(page), 0, page_bytes_ - kPageHeaderBytes);  // a fresh mapping's are
  pages_.push_back(page);
  shared_.push_back(0);
  count_live(1);
}

void PageTable::push_back_fresh(std::size_t n) {
  pages_.reserve(pages_.size() + n);
  shared_.reserve(shared_.size() + n);
  allocate_written_blocks(page_bytes_, n, [&](void* memory) {
    PageHeader* page = start_page(memory, page_bytes_, ledger_.get());
    if (!comes_zeroed(page_bytes_)) std::memset(items(page), 0, page_bytes_ - kPageHeaderBytes);
    pages_.push_back(page);
    shared_.push_back(0);
  });
  count_live(std::ptrdiff_t(n));
}

void PageTable::resize_down(std::size_t n) {
  if (n >= pages_.size()) return;
  count_live(-std::ptrdiff_t(pages_.size() - n));
  for (std::size_t i = n; i < pages_.size(); ++i) let_go(pages_[i]);
  pages_.resize(n);
  shared_.resize(n);
}

void PageTable::count_live(std::ptrdiff_t pages) const {
  if (live_ && ledger_) ledger_->live_bytes.fetch_add(std::size_t(pages) * page_bytes_, std::memory_order_relaxed);
}

std::size_t PageTable::release_replaced() {
  const std::size_t bytes = replaced_.size() * page_bytes_;
  for (PageHeader* page : replaced_) let_go(page);
  replaced_.clear();
  return bytes;
}

PageHeader* PageLedger::take_spare(std::size_t page_bytes) {
  const std::lock_guard lock(mutex_);
  for (Spare& s : spare_) {
    if (s.page_bytes != page_bytes || s.pages.empty()) continue;
    PageHeader* page = s.pages.back();
    s.pages.pop_back();
    spare_bytes_ -= page_bytes;
    return page;
  }
  return nullptr;
}

void PageLedger::keep_spare(PageHeader* page) {
  const std::lock_guard lock(mutex_);
  auto s = std::find_if(spare_.begin(), spare_.end(), [&](const Spare& x) { return x.page_bytes == page->bytes; });
  if (s == spare_.end()) s = spare_.insert(spare_.end(), Spare{page->bytes, {}});
  s->pages.push_back(page);
  spare_bytes_ += page->bytes;
}

void PageLedger::trim_spare(std::size_t keep) {
  std::vector<PageHeader*> gone;
  {
    const std::lock_guard lock(mutex_);
    for (Spare& s : spare_) {
      while (spare_bytes_ > keep && !s.pages.empty()) {
        gone.push_back(s.pages.back());
        spare_bytes_ -= s.page_bytes;
        s.pages.pop_back();
      }
    }
  }
  // pages that lie end to end (mapped together: PageTable::push_back_fresh) go back in one call
  std::sort(gone.begin(), gone.end());
  // (a page from the heap, where allocations are not mapped, goes back on its own)
  const auto joins = [&](std::size_t i, const std::byte* end) {
    return allocations_are_mapped() && i < gone.size() && reinterpret_cast<std::byte*>(gone[i]) == end;
  };
  for (std::size_t i = 0; i < gone.size();) {
    auto* const first = reinterpret_cast<std::byte*>(gone[i]);
    std::size_t run = 0;
    do {
      run += gone[i]->bytes;
      gone[i++]->~PageHeader();
    } while (joins(i, first + run));
    bytes.fetch_sub(run, std::memory_order_relaxed);
    release_bytes(first, run);
  }
}

PageTable PageTable::share() {
  PageTable copy(page_bytes_, ledger_);
  copy.live_ = false;
  copy.pages_ = pages_;
  copy.shared_.assign(pages_.size(), 1);
  for (PageHeader* page : pages_) page->holders.fetch_add(1, std::memory_order_relaxed);
  std::fill(shared_.begin(), shared_.end(), std::uint8_t{1});
  return copy;
}

void PageTable::unshare(std::size_t i) {
  shared_[i] = 0;
  PageHeader* page = pages_[i];
  // acquire: a holder that let go finished reading before this table writes in place
  if (page->holders.load(std::memory_order_acquire) == 1) return;
  PageHeader* copy = new_page(page_bytes_, ledger_.get()).page;
  std::memcpy(items(copy), items(page), page_bytes_ - kPageHeaderBytes);
  pages_[i] = copy;
  replaced_.push_back(page);
}

void PageTable::let_go(PageHeader* page) const {
  // acq_rel: the last holder sees every other holder's reads finished before it frees the page
  if (page->holders.fetch_sub(1, std::memory_order_acq_rel) != 1) return;
  page->ledger->keep_spare(page);
}

}  // namespace eco::detail
