// Occupied voxels of a world-aligned grid.
//
// When the voxel side is a lattice cell side (Quantised mode, resolution = voxel_size * 2^i), a
// node at the voxel's depth is one voxel and its points need not be looked at — nor the node
// itself: its parent lists its children as voxels (no node is empty between updates). A leaf one
// or two levels above the voxels lists the subcells it keeps occupied. The map costs a visit per
// node above the voxels plus the points of leaves coarser still (marked in a bitmask against the
// lattice walls inside the leaf). Distinct leaves never share a voxel then, so a leaf's keys are
// made unique within the leaf and the map needs no global sort.
// Any other resolution visits every point and sorts.

#include "core/geometry/subcells.hpp"
#include "query/frames.hpp"
#include "query/queries.hpp"


#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <cmath>
#include <optional>
#include <sstream>

namespace eco {
namespace detail {
namespace {

/// The voxel's depth in the lattice, as `unit_shift`: a voxel is 2^unit_shift lattice units
/// (negative: finer than the smallest cell). None when voxels do not fall on the lattice.
std::optional<int> lattice_shift(const Tree& t, double resolution) {
  if (t.config().recentring != Recentring::Quantised || !(t.config().voxel_size > 0.0)) return std::nullopt;
  const int k = int(t.config().quantum_levels);
  for (int shift = t.lattice().max_depth - k; shift >= -30; --shift) {
    if (std::ldexp(t.lattice().unit, shift) == resolution) return shift;
  }
  return std::nullopt;
}

void require_representable(const Tree& t, double resolution) {
  if (t.root() == kNone || t.nodes()[t.root()].count == 0) return;
  const Aabb& b = t.nodes()[t.root()].bounds;
  double reach = 0.0;
  for (int a = 0; a < 3; ++a) {
    reach = std::max({reach, std::abs(t.motion().anchor[a] + double(b.lo[a])), std::abs(t.motion().anchor[a] + double(b.hi[a]))});
  }
  if (!grid_fits(reach + 1.0, resolution)) {
    std::ostringstream s;
    s << "eco::EgoOctree::voxel_keys: resolution = " << resolution << " m cannot index points " << reach
      << " m from the world origin (more than 2^50 voxels)";
    throw std::invalid_argument(s.str());
  }
}

/// The smallest float not below w: for any float p, p >= result exactly when double(p) >= w.
float float_at_or_above(double w) {
  const auto f = float(w);
  return double(f) < w ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

class LatticeVoxels {
 public:
  LatticeVoxels(const Tree& t, double resolution, int shift, std::vector<VoxelKey>& out)
      : t_(t),
        grid_({t.motion().anchor[0], t.motion().anchor[1], t.motion().anchor[2]}, resolution),
        shift_(shift),
        depth_(t.lattice().max_depth - shift),
        out_(out) {}

  void collect(std::uint32_t id, const Cell& cell) {
    const Node& n = t_.nodes()[id];
    if (n.count == 0) return;
    if (cell.depth == depth_) {  // the node is one voxel
      out_.push_back(voxel_of(cell));
      return;
    }
    if (n.leaf) {
      if (shift_ >= 0 && depth_ - cell.depth <= 2) {
        collect_subcells(n, cell);
      } else if (shift_ >= 0 && depth_ - cell.depth == kMaskLevels) {
        collect_masked(n, cell);
      } else {
        collect_sorted(n);
      }
      return;
    }
    if (cell.depth + 1 == depth_) {  // the children are one voxel each, and none is empty (check_tree)
      t_.nodes().for_each_child(id, [&](int o, std::uint32_t) { out_.push_back(voxel_of(t_.lattice().child(cell, o))); });
      return;
    }
    t_.nodes().prefetch_children(id);
    t_.nodes().for_each_child(id, [&](int o, std::uint32_t ch) { collect(ch, t_.lattice().child(cell, o)); });
  }

 private:
  /// A leaf this many levels above the voxels marks its voxels in a bitmask (8^3 bits); nearer
  /// ones list their subcells.
  static constexpr int kMaskLevels = 3;

  /// The voxel whose lower corner is `cell`'s (a cell at or above the voxels' depth).
  [[nodiscard]] VoxelKey voxel_of(const Cell& cell) const {
    return {cell.lo[0] >> shift_, cell.lo[1] >> shift_, cell.lo[2] >> shift_};
  }

  /// A leaf one or two levels above the voxels: its voxels are its subcells, kept with it
  /// (core/geometry/subcells.hpp; their walls are the voxels' down to the lattice's finest cells).
  void collect_subcells(const Node& n, const Cell& cell) {
    const VoxelKey first = voxel_of(cell);
    if (depth_ - cell.depth == 2) {
      for (std::uint64_t bits = n.subcells(); bits != 0; bits &= bits - 1) {
        const int b = std::countr_zero(bits);
        out_.push_back({first.x + (b & 3), first.y + (b >> 2 & 3), first.z + (b >> 4)});
      }
      return;
    }
    for (unsigned bits = halved(n.subcells()); bits != 0; bits &= bits - 1) {
      const int b = std::countr_zero(bits);
      out_.push_back({first.x + (b & 1), first.y + (b >> 1 & 1), first.z + (b >> 2)});
    }
  }

  /// Marks the voxel of each point of leaf `n` (cell `cell`, kMaskLevels above the voxels) in a
  /// bitmask, found by comparing with the lattice walls inside the cell, then lists the marked
  /// voxels: no division, no sort (loops of a known length: unrolled, without branches).
  void collect_masked(const Node& n, const Cell& cell) {
    constexpr int per_axis = 1 << kMaskLevels;
    const std::int64_t step = t_.lattice().side(depth_);
    std::array<std::array<float, per_axis - 1>, 3> walls{};  // the inner walls
    for (int a = 0; a < 3; ++a) {
      for (int j = 1; j < per_axis; ++j) {
        walls[a][std::size_t(j - 1)] = float_at_or_above(t_.lattice().wall(a, cell.lo[a] + j * step));
      }
    }
    // one word for up to 64 voxels: kept in a register, not read back from memory every point
    std::array<std::uint64_t, (per_axis * per_axis * per_axis + 63) / 64> marked{};
    const PointSpan points = t_.points().span(n.link, n.count);
    for (std::uint32_t i = 0; i < points.size; ++i) {
      const std::array<float, 3> p{points.x[i], points.y[i], points.z[i]};
      std::array<int, 3> sub{};
      for (int a = 0; a < 3; ++a) {
        for (int j = 0; j + 1 < per_axis; ++j) sub[a] += int(p[a] >= walls[a][std::size_t(j)]);
      }
      const int bit = (sub[2] * per_axis + sub[1]) * per_axis + sub[0];
      marked[std::size_t(bit >> 6)] |= std::uint64_t{1} << (bit & 63);
    }
    const VoxelKey first = voxel_of(cell);
    for (std::size_t w = 0; w < marked.size(); ++w) {
      for (std::uint64_t bits = marked[w]; bits != 0; bits &= bits - 1) {
        const int bit = int(w * 64) + std::countr_zero(bits);
        out_.push_back({first.x + bit % per_axis, first.y + bit / per_axis % per_axis,
                        first.z + bit / (per_axis * per_axis)});
      }
    }
  }

  /// A leaf far coarser than a voxel: the points' keys, made unique within the leaf.
  void collect_sorted(const Node& n) {
    const std::size_t base = out_.size();
    t_.points().for_each(n.link, n.count, [&](const StoredPoint& s) {
      const VoxelKey key{grid_.index(0, s.p[0]), grid_.index(1, s.p[1]), grid_.index(2, s.p[2])};
      if (out_.size() == base || out_.back() != key) out_.push_back(key);
    });
    sort_unique(out_, base);
  }

  const Tree& t_;
  WorldGrid grid_;
  int shift_;
  int depth_;
  std::vector<VoxelKey>& out_;
};

}  // namespace

std::vector<VoxelKey> voxel_keys_of(const Tree& t, double resolution) {
  require_positive(resolution, "voxel_keys", "resolution", false);
  require_representable(t, resolution);
  std::vector<VoxelKey> keys;
  if (t.root() == kNone) return keys;
  if (const std::optional<int> shift = lattice_shift(t, resolution)) {
    LatticeVoxels(t, resolution, *shift, keys).collect(t.root(), t.root_cell());
    return keys;
  }
  keys.reserve(t.nodes()[t.root()].count);
  const Eigen::Vector3d anchor = t.motion().anchor;
  const WorldGrid grid({anchor[0], anchor[1], anchor[2]}, resolution);
  walk_leaves(
      t, t.root(), [](const Aabb&) { return 2; },
      [&](const StoredPoint& s, bool) {
        const VoxelKey key{grid.index(0, s.p[0]), grid.index(1, s.p[1]), grid.index(2, s.p[2])};
        if (keys.empty() || keys.back() != key) keys.push_back(key);  // neighbours often repeat
      });
  sort_unique(keys);
  return keys;
}

void sort_unique(std::vector<VoxelKey>& keys, std::size_t from) {
  const auto first = keys.begin() + std::ptrdiff_t(from);
  std::sort(first, keys.end());
  keys.erase(std::unique(first, keys.end()), keys.end());
}

}  // namespace detail

}  // namespace eco
