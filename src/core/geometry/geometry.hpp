#pragma once
// Boxes and cells. All coordinates here are in the "anchor frame": world minus the precision
// origin. Stored points and AABBs are float; cell walls and the ego box are double.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace eco::detail {

/// The cell index i with i*size - origin <= stored < (i+1)*size - origin, the walls computed in
/// double, found from any `guess` near it (the guess is off by a step or two at most).
inline std::int64_t settle_grid_index(std::int64_t guess, double origin, double stored, double size) {
  while (stored < double(guess) * size - origin) --guess;
  while (stored >= double(guess + 1) * size - origin) ++guess;
  return guess;
}

/// Index of the world-aligned grid cell of side `size` holding a stored coordinate: the i with
/// i*size - origin <= stored < (i+1)*size - origin, the walls computed in double (the contract's
/// rule for density cells and voxels). These are the tree's own lattice walls when `size` is a
/// lattice cell side, so cells and voxels agree to the last bit. The caller guarantees
/// grid_fits(); then the floor is off by at most one step and the walls settle it.
inline std::int64_t world_grid_index(double origin, float stored, double size) {
  const double f = stored;
  return settle_grid_index(std::int64_t(std::floor((origin + f) / size)), origin, f, size);
}

/// world_grid_index for many points of one grid: a multiplication by 1/size and a truncation
/// make the guess (a division and a floor call per axis cost the density cap ~1/4 of its update).
/// The truncation is taken of a positive number — the index counted from a base below the
/// origin's cell — so that it is the floor: a truncation of a negative one is off by one, and
/// the walls' loops then mispredict on every point on that side of the origin.
///
/// A guess whose fraction lies more than kSure from both its walls is the answer without
/// computing them. Why: in cell units, with M = max(|origin|, |stored|, |index * size|) / size,
/// the guess is within 4 M 2^-52 of (stored + origin) / size (one rounding each for the sum, 1/size,
/// the product and the base's subtraction), and each wall double(i) * size - origin within
/// 3 M 2^-53 of i - origin / size. Below kFastCells cells from the origin's (|origin| / size
/// under kFastCells too), M < 2^36 and both errors stay under 2^-14 < kSure / 2: a point kSure
/// inside its cell by the guess is inside it by the walls. Other points settle on the walls.
class WorldGrid {
 public:
  /// `origin`: the precision origin the stored coordinates are relative to.
  WorldGrid(const std::array<double, 3>& origin, double size) : origin_(origin), size_(size), inverse_(1.0 / size) {
    for (int a = 0; a < 3; ++a) {
      base_[a] = std::floor(origin[a] * inverse_) - kReach;
      fast_below_[a] = std::abs(origin[a] * inverse_) < kFastCells ? kFastCells : -1.0;  // -1: never
    }
  }
  /// The same grid, its guesses made in single precision (twice the lanes) for the stored
  /// coordinates near `centre` when those within `reach` of it (the ego box's centre and half
  /// side) lie within kSingleReach cells and the origin and the centre within kFastCells of the
  /// world's origin; see Single.
  WorldGrid(const std::array<double, 3>& origin, double size, const std::array<double, 3>& centre, double reach)
      : WorldGrid(origin, size) {
    bool ready = reach * inverse_ < kSingleReach;
    for (int a = 0; a < 3; ++a) {
      const float near = float(centre[a]);
      const double cells = (origin[a] + double(near)) * inverse_;
      ready = ready && std::abs(cells) < kFastCells && fast_below_[a] > 0.0;  // both within 2^34 cells
      const double below = std::floor(cells) - kSingleReach;  // exact: cells < 2^34
      single_.axis[a] = {near, float(cells - below), std::int64_t(below)};
    }
    single_.inverse = float(inverse_);
    single_.ready = ready;
  }

  /// What the single-precision guess (core/density/density_gate.cpp) computes with. Stored coordinate s
  /// lies g = offset + (s - near) * inverse cells above cell `base`, everything in float; a g in
  /// [0, 2 kSingleReach) whose fraction lies more than kSure from both its walls is the answer.
  /// Why, in cell units (M < 2^34 the origin's and the centre's cells from the world's origin,
  /// |s - near| below kSingleReach = 2^8 cells): s - near, the float inverse and their product are
  /// each rounded once (3 · 2^8 · 2^-24 = 3 · 2^-16), the offset to float once and the sum once
  /// (2^-16 each, g < 2^9), the offset in double and the walls by 3 M 2^-53 < 2^-17 each: in all
  /// under 46 · 2^-19 < 2^-13, half of kSure.
  struct Single {
    struct Axis {
      float near, offset;
      std::int64_t base;
    };
    std::array<Axis, 3> axis{};
    float inverse = 0.0f;
    bool ready = false;  // else the guesses are made in double
  };
  [[nodiscard]] const Single& single() const { return single_; }
  static constexpr double kSingleReach = 0x1p8;  // cells either side of the centre's guessed in float

  /// What index() computes with, per axis, for vector code that makes the same guesses
  /// (core/density/density_gate.cpp): a guess is sure where its fraction lies in (kSure, 1 - kSure) and
  /// |cells| below fast_below.
  struct Axis {
    double origin, base, fast_below;
  };
  [[nodiscard]] Axis axis(int a) const { return {origin_[a], base_[a], fast_below_[a]}; }
  [[nodiscard]] double inverse() const { return inverse_; }
  static constexpr double kSure = 0x1p-12;  // a guess this far inside its cell needs no walls
  static constexpr double kReach = 0x1p30;  // cells either side of the origin's guessed at once

  [[nodiscard]] std::array<std::int64_t, 3> index(const std::array<float, 3>& stored) const {
    return {index(0, stored[0]), index(1, stored[1]), index(2, stored[2])};
  }
  [[nodiscard]] std::int64_t index(int axis, float stored) const {
    const double f = stored;
    const double cells = (origin_[axis] + f) * inverse_;
    // within kReach cells of the origin's the difference is positive and below 2^53, so its
    // truncation is its floor and its fraction is exact
    const double above_base = cells - base_[axis];
    const auto whole = std::int64_t(above_base);
    const std::int64_t guess = whole + std::int64_t(base_[axis]);
    const double fraction = above_base - double(whole);
    if (fraction > kSure && fraction < 1.0 - kSure && std::abs(cells) < fast_below_[axis]) return guess;
    return settle_grid_index(guess, origin_[axis], f, size_);
  }

 private:
  static constexpr double kFastCells = 0x1p34;  // kSure's guess needs no walls when the point and the origin lie within this

  std::array<double, 3> origin_;
  std::array<double, 3> base_{};
  std::array<double, 3> fast_below_{};
  double size_, inverse_;
  Single single_;
};

/// Whether the grid of side `size` names every coordinate within `reach` metres of the world
/// origin by an exact 64-bit index with distinct walls: reach / size below 2^50.
inline bool grid_fits(double reach, double size) {
  return std::isfinite(reach) && size > 0 && reach / size < 0x1p50;
}

/// Tight bounds of the points below a node (float, like the points).
struct Aabb {
  std::array<float, 3> lo{inf(), inf(), inf()};
  std::array<float, 3> hi{-inf(), -inf(), -inf()};

  static constexpr float inf() { return std::numeric_limits<float>::infinity(); }
  [[nodiscard]] bool empty() const { return lo[0] > hi[0]; }
  void grow(float x, float y, float z) {
    lo = {std::min(lo[0], x), std::min(lo[1], y), std::min(lo[2], z)};
    hi = {std::max(hi[0], x), std::max(hi[1], y), std::max(hi[2], z)};
  }
  void merge(const Aabb& o) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], o.lo[a]);
      hi[a] = std::max(hi[a], o.hi[a]);
    }
  }
  /// Squared distance from q to the nearest point of the box (0 inside).
  [[nodiscard]] double sq_dist(const std::array<double, 3>& q) const {
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double d = std::max({double(lo[a]) - q[a], 0.0, q[a] - double(hi[a])});
      d2 += d * d;
    }
    return d2;
  }
};

/// An axis-aligned box in double. `half_open` boxes are [lo, hi); closed ones [lo, hi].
struct Box {
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};
  bool half_open = true;

  [[nodiscard]] bool contains(double x, double y, double z) const {
    const std::array<double, 3> p{x, y, z};
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo[a] || p[a] > hi[a] || (half_open && p[a] == hi[a])) return false;
    }
    return true;
  }
  [[nodiscard]] bool contains_all(const Aabb& b) const {
    return contains(b.lo[0], b.lo[1], b.lo[2]) && contains(b.hi[0], b.hi[1], b.hi[2]);
  }
  [[nodiscard]] bool misses(const Aabb& b) const {
    for (int a = 0; a < 3; ++a) {
      if (double(b.hi[a]) < lo[a] || double(b.lo[a]) > hi[a]) return true;
      if (half_open && double(b.lo[a]) >= hi[a]) return true;
    }
    return false;
  }
};

/// A cell of the tree: its lower corner in lattice units and its depth. The side of a cell at
/// depth d is 2^(max_depth - d) units. Cells name walls by integers so that a wall computed via
/// any path through the tree is the same double.
struct Cell {
  std::array<std::int64_t, 3> lo{};
  int depth = 0;
};

/// Turns lattice units into anchor-frame metres: wall(G) = origin + G * unit.
/// Quantised mode: origin = -precision_origin and G is a world lattice index, so the lattice is
/// fixed in the world. Exact mode: origin = the root's lower corner and G counts from it.
struct Lattice {
  std::array<double, 3> origin{};
  double unit = 1.0;
  int max_depth = 0;

  [[nodiscard]] std::int64_t side(int depth) const { return std::int64_t{1} << (max_depth - depth); }
  [[nodiscard]] double wall(int axis, std::int64_t g) const {
    return origin[axis] + double(g) * unit;
  }
  [[nodiscard]] bool contains(const Cell& c, const std::array<float, 3>& p) const {
    const std::int64_t s = side(c.depth);
    for (int a = 0; a < 3; ++a) {
      if (double(p[a]) < wall(a, c.lo[a]) || double(p[a]) >= wall(a, c.lo[a] + s)) return false;
    }
    return true;
  }
  [[nodiscard]] bool contains(const Cell& c, const Aabb& b) const {
    return contains(c, b.lo) && contains(c, b.hi);
  }
  /// Which of the eight children of `c` holds p (bit a set: upper half along axis a); p stored
  /// (float) or a query (double).
  template <class Coordinate>
  [[nodiscard]] int octant(const Cell& c, const std::array<Coordinate, 3>& p) const {
    return octant_within(middle(c), double(p[0]), double(p[1]), double(p[2]));
  }
  /// The walls between the children of `c`, one per axis: octant()'s, found once for many points.
  [[nodiscard]] std::array<double, 3> middle(const Cell& c) const {
    const std::int64_t half = side(c.depth) / 2;
    return {wall(0, c.lo[0] + half), wall(1, c.lo[1] + half), wall(2, c.lo[2] + half)};
  }
  /// The octant of (x, y, z) among the children whose walls are `middle`.
  [[nodiscard]] static int octant_within(const std::array<double, 3>& middle, double x, double y, double z) {
    return int(x >= middle[0]) | int(y >= middle[1]) << 1 | int(z >= middle[2]) << 2;
  }
  /// Which child of `c` holds the smaller cell `inner` (integer walls only: exact).
  [[nodiscard]] int octant_of(const Cell& c, const Cell& inner) const {
    const std::int64_t half = side(c.depth) / 2;
    int o = 0;
    for (int a = 0; a < 3; ++a) {
      if (inner.lo[a] >= c.lo[a] + half) o |= 1 << a;
    }
    return o;
  }
  /// Whether cell `inner` lies inside cell `c`.
  [[nodiscard]] bool encloses(const Cell& c, const Cell& inner) const {
    for (int a = 0; a < 3; ++a) {
      if (inner.lo[a] < c.lo[a] || inner.lo[a] + side(inner.depth) > c.lo[a] + side(c.depth)) {
        return false;
      }
    }
    return true;
  }
  [[nodiscard]] Cell child(const Cell& c, int octant) const {
    const std::int64_t half = side(c.depth) / 2;
    Cell k{c.lo, c.depth + 1};
    for (int a = 0; a < 3; ++a) {
      if (octant & (1 << a)) k.lo[a] += half;
    }
    return k;
  }
  /// The cells at `depth` as a world grid: cell index j is the cell whose lower corner is
  /// j * side(depth) units, its walls the same doubles as wall() gives (side(depth) * unit is a
  /// power-of-two multiple of unit, so the products round alike; x - (-o) is o + x).
  [[nodiscard]] WorldGrid grid(int depth) const {
    return WorldGrid({-origin[0], -origin[1], -origin[2]}, double(side(depth)) * unit);
  }
  /// The cell at `depth` that holds p: agrees with octant() descents exactly.
  [[nodiscard]] Cell cell_at(int depth, const std::array<float, 3>& p) const { return cell_of(depth, grid(depth).index(p)); }
  /// The cell at `depth` whose index in grid(depth) is j.
  [[nodiscard]] Cell cell_of(int depth, const std::array<std::int64_t, 3>& j) const {
    const std::int64_t s = side(depth);
    return {{j[0] * s, j[1] * s, j[2] * s}, depth};
  }
};

}  // namespace eco::detail
