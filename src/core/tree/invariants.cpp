// check_tree (EgoOctree::check_invariants): every structural promise of the tree, checked from scratch.

#include "core/geometry/subcells.hpp"
#include "core/tree/tree.hpp"
#include "core/tree/invariants.hpp"


#include <sstream>

namespace eco {
namespace {

class Checker {
 public:
  Checker(const detail::Tree& t, bool in_box) : t_(t), box_(t.motion().box), in_box_(in_box) {}

  std::string run() {
    if (t_.root() == detail::kNone) return t_.motion().frame == 0 ? "" : "no root after an update";
    if (t_.nodes()[t_.root()].parent != detail::kNone) fail(t_.root(), "root has a parent");
    check(t_.root(), t_.root_cell());
    if (t_.nodes().live() != seen_) fail(t_.root(), "live node count differs from reachable nodes");
    return error_.str();
  }

 private:
  void fail(std::uint32_t id, const std::string& what) {
    if (error_.tellp() == 0) error_ << "node " << id << ": " << what;
  }

  void check(std::uint32_t id, const detail::Cell& cell) {
    ++seen_;
    const detail::Node& n = t_.nodes()[id];
    if (n.depth != cell.depth) fail(id, "depth differs from its cell's");
    detail::Aabb bounds;
    std::uint32_t count = 0;
    std::uint32_t oldest = detail::kNone;
    if (n.leaf) {
      if (n.depth < detail::min_leaf_depth(t_.config()) && id != t_.root()) fail(id, "leaf above the lattice depth");
      if (n.count > t_.config().leaf_capacity && n.depth < t_.lattice().max_depth) {
        fail(id, "overfull leaf above the minimum cell size");
      }
      if (n.link != detail::kNone && t_.points().owner_of(n.link) != id) fail(id, "its block names another owner");
      const detail::Subcells walls(t_.lattice(), cell);
      std::uint64_t subcells = 0;
      t_.points().for_each(n.link, n.count, [&](const detail::StoredPoint& s) {
        ++count;
        bounds.grow(s.p[0], s.p[1], s.p[2]);
        oldest = std::min(oldest, t_.age_limit().key(s));
        if (!t_.lattice().contains(cell, s.p)) fail(id, "point outside its cell");
        if (in_box_ && !box_.contains(s.p[0], s.p[1], s.p[2])) fail(id, "point outside the ego box");
        subcells |= std::uint64_t{1} << walls.of(s.p);
      });
      if (t_.config().recentring == Recentring::Quantised && subcells != n.subcells()) fail(id, "occupied subcells wrong");
    } else {
      bool any = false;
      t_.nodes().for_each_child(id, [&](int o, std::uint32_t ch) {
        any = true;
        const detail::Node& c = t_.nodes()[ch];
        if (c.parent != id || c.octant != o) fail(ch, "parent link broken");
        check(ch, t_.lattice().child(cell, o));
        count += c.count;
        bounds.merge(c.bounds);
        oldest = std::min(oldest, c.oldest);
      });
      if (!any && id != t_.root()) fail(id, "inner node without children");
      if (n.depth >= detail::min_leaf_depth(t_.config()) && n.count <= t_.config().leaf_capacity && id != t_.root()) {
        fail(id, "inner node small enough to be a leaf");
      }
    }
    if (count != n.count) fail(id, "count differs from its points");
    if (count == 0 && id != t_.root()) fail(id, "empty node kept");
    if (bounds.lo != n.bounds.lo || bounds.hi != n.bounds.hi) fail(id, "bounds not tight");
    if (oldest != n.oldest) fail(id, "oldest stamp wrong");
  }

  const detail::Tree& t_;
  detail::Box box_;
  bool in_box_;
  std::size_t seen_ = 0;
  std::ostringstream error_;
};

}  // namespace

namespace detail {
std::string check_tree(const Tree& t, bool in_box) { return Checker(t, in_box).run(); }
}  // namespace detail

}  // namespace eco
