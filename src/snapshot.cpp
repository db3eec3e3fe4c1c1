// A snapshot: a read-only tree sharing the live tree's pages (core/storage/shared_pages.hpp).

#include "core/tree/tree.hpp"

#include <eco/snapshot.hpp>

namespace eco {

Snapshot::Snapshot(std::unique_ptr<const detail::Tree> tree) : tree_(std::move(tree)) {}
Snapshot::~Snapshot() = default;
const detail::Tree& Snapshot::held() const { return *tree_; }

}  // namespace eco
