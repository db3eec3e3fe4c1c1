// Linear probing over a power-of-two table kept at most half used.

#include "view/birth_table.hpp"

#include <bit>
#include <limits>

namespace eco::view {
namespace {

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

std::uint64_t hash(double x, double y, double z) {
  std::uint64_t h = bits(x) * 0x9e3779b97f4a7c15ull ^ std::rotl(bits(y) * 0xc2b2ae3d27d4eb4full, 21) ^
                    std::rotl(bits(z) * 0x165667b19e3779f9ull, 42);
  h ^= h >> 29;  // the mantissas' low bits differ between neighbours: bring the high ones down
  h *= 0xbf58476d1ce4e5b9ull;
  return h ^ (h >> 32);
}

bool same(const BirthTable::Entry& e, double x, double y, double z) {
  return bits(e.x) == bits(x) && bits(e.y) == bits(y) && bits(e.z) == bits(z);
}

}  // namespace

BirthTable::Entry& BirthTable::at(const Eigen::Vector3d& p, std::uint32_t frame) {
  if (2 * (used_ + 1) > slots_.size()) grow();
  const std::size_t mask = slots_.size() - 1;
  std::size_t free = slots_.size();
  for (std::size_t i = hash(p.x(), p.y(), p.z()) & mask;; i = (i + 1) & mask) {
    Entry& e = slots_[i];
    if (e.x == kEmpty) {
      if (free == slots_.size()) {
        free = i;
        ++used_;  // a fresh slot; a deleted one reused was counted already
      }
      break;
    }
    if (e.x == kDeleted) {
      if (free == slots_.size()) free = i;
      continue;
    }
    if (same(e, p.x(), p.y(), p.z())) return e;
  }
  ++live_;
  return slots_[free] = Entry{p.x(), p.y(), p.z(), frame, 0, 0};
}

void BirthTable::grow() {
  std::vector<Entry> old = std::move(slots_);
  std::size_t size = 1024;
  while (size < 4 * (live_ + 1)) size *= 2;
  slots_.assign(size, Entry{kEmpty, 0, 0, 0, 0, 0});
  used_ = live_;
  const std::size_t mask = size - 1;
  for (const Entry& e : old) {
    if (!live(e)) continue;
    std::size_t i = hash(e.x, e.y, e.z) & mask;
    while (slots_[i].x != kEmpty) i = (i + 1) & mask;
    slots_[i] = e;
  }
}

}  // namespace eco::view
