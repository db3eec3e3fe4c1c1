// Exact k-nearest neighbours: depth-first, children in order of their cells' distance, pruned by
// the current k-th distance — first by the cell (from the lattice walls: no child read), then by
// the child's tight bounds.

#include "query/distances.hpp"
#include "query/frames.hpp"
#include "query/queries.hpp"


#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace eco {
namespace {

/// Whether more than `count` of the bits are set (counted no further: the baseline x86-64 has no
/// popcount instruction).
bool more_bits_than(std::uint64_t bits, std::size_t count) {
  for (std::size_t i = 0; i <= count; ++i, bits &= bits - 1) {
    if (bits == 0) return false;
  }
  return true;
}

/// A result as a reference to a held point (a leaf's block and an index in it), written out as a
/// Neighbor when the search ends: an insertion shifts 16 bytes an entry, not a Neighbor's 48.
struct Candidate {
  double sq_dist;
  std::uint32_t link;
  std::uint32_t index;
};

/// Results ranked in a span of entries that carry their sq_dist, nearest first.
template <class Entry>
class RankedSpan {
 public:
  explicit RankedSpan(std::span<Entry> out) : out_(out) {}
  [[nodiscard]] std::size_t capacity() const { return out_.size(); }
  [[nodiscard]] double sq_dist(std::size_t i) const { return out_[i].sq_dist; }
  void move_down(std::size_t i) { out_[i] = out_[i - 1]; }

 protected:
  std::span<Entry> out_;
};

class CandidateResults : public RankedSpan<Candidate> {
 public:
  using RankedSpan::RankedSpan;
  void put(std::size_t i, double d2, const detail::PointSpan&, std::uint32_t link, std::uint32_t j) {
    out_[i] = {d2, link, j};
  }
};

/// Results as Neighbors: points in the anchor frame until the search ends (stored floats, held
/// exactly in double), attributes as stored. For a k beyond CandidateResults' stack.
class NeighborResults : public RankedSpan<Neighbor> {
 public:
  using RankedSpan::RankedSpan;
  void put(std::size_t i, double d2, const detail::PointSpan& c, std::uint32_t /*link*/, std::uint32_t j) {
    out_[i] = as_stored(c[j], d2);
  }

  /// A held point as a Neighbor in the anchor frame, its time as stored (knn_query converts both).
  static Neighbor as_stored(const detail::StoredPoint& s, double d2) {
    return {{s.p[0], s.p[1], s.p[2]}, d2, {s.id, s.intensity, double(s.time)}};
  }
};

/// Results as ids and squared distances (nanoflann's style).
class IdResults {
 public:
  IdResults(std::span<std::uint32_t> ids, std::span<double> sq_dists) : ids_(ids), sq_dists_(sq_dists) {}
  [[nodiscard]] std::size_t capacity() const { return ids_.size(); }
  [[nodiscard]] double sq_dist(std::size_t i) const { return sq_dists_[i]; }
  void move_down(std::size_t i) {
    ids_[i] = ids_[i - 1];
    sq_dists_[i] = sq_dists_[i - 1];
  }
  void put(std::size_t i, double d2, const detail::PointSpan& c, std::uint32_t /*link*/, std::uint32_t j) {
    ids_[i] = c.ids[j];
    sq_dists_[i] = d2;
  }

 private:
  std::span<std::uint32_t> ids_;
  std::span<double> sq_dists_;
};

/// Searches into the caller's buffers (no allocation per query): `results` keeps the best so
/// far, nearest first.
template <class Results>
class KnnSearch {
 public:
  KnnSearch(const detail::Tree& t, const std::array<double, 3>& q, Results results)
      : t_(t), q_(q), results_(results) {}

  /// The number found: min(k, points held).
  ///
  /// Bottom-up: the deepest node whose cell holds the query is searched first, then each ancestor
  /// with the child already searched left out, until the k-th distance lies inside the cell just
  /// searched — no point outside it can be nearer (as for the cells' pruning below, rounding keeps
  /// the bound) — or the root has been searched.
  std::size_t run() {
    if (results_.capacity() == 0 || t_.root() == detail::kNone) return found_;
    const detail::Lattice& lattice = t_.lattice();
    Step path[kMaxPath];  // trivial, so left unwritten until used (zeroing it was ~10 % of a query)
    std::size_t deepest = 0;
    path[0] = Step(t_.root(), t_.root_cell());
    if (inside_gap(path[0].cell()) > 0.0) {
      // The way down compares the query's lattice index with the cells' integer walls: a guess
      // where rounding puts it within an ulp of a wall, and harmless there, since only the
      // search's order follows the path; what the search skips is decided by the walls in double.
      detail::Cell unit{{}, lattice.max_depth};  // the finest cell holding the query, as guessed
      for (std::size_t a = 0; a < 3; ++a) {
        unit.lo[a] = std::int64_t(std::floor((q_[a] - lattice.origin[a]) / lattice.unit));  // inside the root: no overflow
      }
      while (!t_.nodes()[path[deepest].id].leaf && deepest + 1 < kMaxPath) {
        const Step& at = path[deepest];
        const int o = lattice.octant_of(at.cell(), unit);
        const std::uint32_t child = t_.nodes().child(at.id, o);
        if (child == detail::kNone) break;
        path[deepest + 1] = Step(child, lattice.child(at.cell(), o));
        ++deepest;
      }
    }
    for (std::size_t level = deepest + 1; level-- > 0;) {
      const detail::Cell cell = path[level].cell();
      visit(path[level].id, cell);
      if (found_ == results_.capacity() && worst_ < inside_gap(cell)) break;
      searched_ = path[level].id;
    }
    return found_;
  }

 private:
  /// A node on the way down to the query, with its cell (a trivial type: Cell initialises itself).
  struct Step {
    Step() = default;
    Step(std::uint32_t node, const detail::Cell& c) : id(node), lo(c.lo), depth(c.depth) {}
    [[nodiscard]] detail::Cell cell() const { return {lo, depth}; }
    std::uint32_t id;
    std::array<std::int64_t, 3> lo;
    int depth;
  };
  static constexpr std::size_t kMaxPath = 64;  // nodes from the root down: more than Config's deepest level

  /// The squared distance from the query to the nearest wall of `cell`, from inside (0 outside).
  [[nodiscard]] double inside_gap(const detail::Cell& cell) const {
    const detail::Lattice& lattice = t_.lattice();
    const std::int64_t side = lattice.side(cell.depth);
    double gap = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < 3; ++a) {
      const double below = q_[a] - lattice.wall(int(a), cell.lo[a]);
      const double above = lattice.wall(int(a), cell.lo[a] + side) - q_[a];
      gap = std::min({gap, below, above});
    }
    return gap > 0.0 ? gap * gap : 0.0;
  }

  [[nodiscard]] double worst() const { return worst_; }

  /// Inserts in order: a shift of the farther ones, cheaper than a heap for the small k of
  /// registration (nanoflann's result sets do the same).
  void offer(double d2, const detail::PointSpan& c, std::uint32_t link, std::uint32_t j) {
    const std::size_t k = results_.capacity();
    if (found_ < k) ++found_;
    std::size_t i = found_ - 1;
    for (; i > 0 && results_.sq_dist(i - 1) > d2; --i) results_.move_down(i);
    results_.put(i, d2, c, link, j);
    if (found_ == k) worst_ = results_.sq_dist(found_ - 1);
  }

  void visit(std::uint32_t id, const detail::Cell& cell) {
    const detail::Node& n = t_.nodes()[id];
    if (n.leaf) {
      const detail::PointSpan c = t_.points().span(n.link, n.count);
      std::array<double, detail::kMaxDistances> d2;
      for (std::uint32_t begin = 0; begin < c.size; begin += detail::kMaxDistances) {
        const auto m = std::min<std::uint32_t>(detail::kMaxDistances, c.size - begin);
        // the points nearer than the k-th distance on entry; each asked again, as offers lower it
        std::uint64_t near = detail::squared_distances(c.x + begin, c.y + begin, c.z + begin, m, q_, worst(), d2.data());
        // Many points nearer than the k-th distance (the first leaf's): most would enter the
        // results only to be pushed out. A bound from eight of them leaves the few that can stay.
        const std::size_t k = results_.capacity();
        if (k <= detail::kGroups && m >= detail::kGroups && more_bits_than(near, 2 * k)) {
          near &= detail::at_most(d2.data(), m, detail::kth_group_minimum(d2.data(), m, k));
        }
        for (; near != 0; near &= near - 1) {
          const auto i = std::uint32_t(std::countr_zero(near));
          if (d2[i] < worst()) offer(d2[i], c, n.link, begin + i);
        }
      }
      return;
    }
    // The children's cells bound their points, and their distances come from the lattice walls
    // without loading a child: a child whose cell lies beyond the k-th distance is never read.
    // (Rounding keeps the bound: a point inside a cell is, axis by axis, no nearer than its walls.)
    const detail::Lattice& lattice = t_.lattice();
    const std::int64_t half = lattice.side(cell.depth) / 2;
    std::array<std::array<double, 2>, 3> gap{};  // per axis: squared gap to the lower, upper half
    for (int a = 0; a < 3; ++a) {
      const double lo = lattice.wall(a, cell.lo[a]), mid = lattice.wall(a, cell.lo[a] + half),
                   hi = lattice.wall(a, cell.lo[a] + 2 * half);
      const double below = std::max({lo - q_[a], 0.0, q_[a] - mid}), above = std::max({mid - q_[a], 0.0, q_[a] - hi});
      gap[std::size_t(a)] = {below * below, above * above};
    }
    // Only the children whose cells lie nearer than the k-th distance are ordered: once it is known
    // (at every ancestor of the first leaf) that is one or two of eight; ordering and prefetching
    // them all cost ~4 % of a query. Per child kept: its cell's squared gap as a word whose order is
    // the gap's (a non-negative double's bits order as integers), its octant in the lowest three
    // bits. The word, read as a double, is a lower bound of the gap, so it prunes soundly. (Sorting
    // gaps and octants side by side by swaps, the compiler loaded pairs of gaps just stored one by
    // one: a stall a child.)
    std::uint64_t order[8];  // of the children kept, then sorted: a plain array, not zeroed
    int m = 0;
    for (int o = 0; o < 8; ++o) {
      const std::uint32_t ch = t_.nodes().child(id, o);
      if (ch == detail::kNone || ch == searched_) continue;  // searched_: before its ancestors
      const double g = gap[0][std::size_t(o & 1)] + gap[1][std::size_t(o >> 1 & 1)] + gap[2][std::size_t(o >> 2)];
      if (g >= worst()) continue;
      t_.nodes().prefetch(ch);  // read below unless pruned by then: the misses overlap
      order[m++] = (std::bit_cast<std::uint64_t>(g) & ~std::uint64_t{7}) | std::uint64_t(o);
    }
    for (int i = 1; i < m; ++i) {  // insertion sort: at most eight children (equal gaps in octant order)
      const std::uint64_t key = order[i];
      int j = i;
      for (; j > 0 && order[j - 1] > key; --j) order[j] = order[j - 1];
      order[j] = key;
    }
    for (int i = 0; i < m; ++i) {
      if (std::bit_cast<double>(order[i] & ~std::uint64_t{7}) >= worst()) break;
      const int o = int(order[i] & 7);
      const std::uint32_t ch = t_.nodes().child(id, o);
      const detail::Node& child = t_.nodes()[ch];
      // then the child's tight bounds, once it is read
      if (child.count > 0 && child.bounds.sq_dist(q_) < worst()) visit(ch, lattice.child(cell, o));
    }
  }

  const detail::Tree& t_;
  std::array<double, 3> q_;
  Results results_;
  std::size_t found_ = 0;
  double worst_ = std::numeric_limits<double>::infinity();  // the k-th distance once k are found
  std::uint32_t searched_ = detail::kNone;                   // the subtree run() searched last
};

}  // namespace

namespace detail {

std::size_t knn_query(const Tree& t, const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame) {
  require_finite(query, "knn", "query");
  const std::array<double, 3> q = to_anchor_frame(t, query, frame);
  constexpr std::size_t kOnStack = 32;  // registration asks for 5-20
  std::size_t found = 0;
  if (out.size() <= kOnStack) {  // references ranked, the points read once at the end
    std::array<Candidate, kOnStack> on_stack;
    const std::span<Candidate> ranked = std::span<Candidate>(on_stack).first(out.size());
    found = KnnSearch(t, q, CandidateResults(ranked)).run();
    for (std::size_t i = 0; i < found; ++i) {
      const Candidate& c = ranked[i];
      out[i] = NeighborResults::as_stored(t.points().span(c.link, c.index + 1)[c.index], c.sq_dist);
    }
  } else {
    found = KnnSearch(t, q, NeighborResults(out)).run();
  }
  const bool times = t.config().attributes.time;
  for (Neighbor& n : out.first(found)) {
    n.point = from_stored(t, {float(n.point[0]), float(n.point[1]), float(n.point[2])}, frame);
    if (times) n.attributes.time = t.motion().clock.seconds(float(n.attributes.time));
  }
  return found;
}

std::size_t knn_ids_query(const Tree& t, const Eigen::Vector3d& query, std::span<std::uint32_t> ids,
                          std::span<double> sq_dists, Frame frame) {
  require_finite(query, "knn", "query");
  if (!t.points().columns().ids) {
    throw std::invalid_argument("eco::EgoOctree::knn: ids asked for, but Config::attributes.ids is off");
  }
  if (ids.size() != sq_dists.size()) {
    throw std::invalid_argument("eco::EgoOctree::knn: ids.size() = " + std::to_string(ids.size()) +
                                " differs from sq_dists.size() = " + std::to_string(sq_dists.size()));
  }
  return KnnSearch(t, to_anchor_frame(t, query, frame), IdResults(ids, sq_dists)).run();
}

}  // namespace detail

}  // namespace eco
