// Lattice and Cell on their own: cell_at agrees with a descent by octant() from the root for
// random points and for points exactly on walls (a wall belongs to the cell above it); children,
// enclosure and octant_of agree with those descents; sides halve per level.

#include "core/geometry/geometry.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace eco::detail {
namespace {

class LatticeTest : public ::testing::Test {
 protected:
  LatticeTest() {
    lattice.origin = {-10.3, 5.1, 0.7};
    lattice.unit = 0.05;
    lattice.max_depth = 9;
    root.lo = {-512, 0, 512};  // cells sit on multiples of their side
    root.depth = 0;
  }

  /// The cells from the root down to `depth` that hold p, by octant().
  std::vector<Cell> descent(const std::array<float, 3>& p, int depth) const {
    std::vector<Cell> path{root};
    while (path.back().depth < depth) path.push_back(lattice.child(path.back(), lattice.octant(path.back(), p)));
    return path;
  }

  /// A float point inside the root cell (not on its upper walls).
  std::array<float, 3> random_point(std::mt19937& rng) const {
    std::array<float, 3> p{};
    const std::int64_t side = lattice.side(0);
    for (int a = 0; a < 3; ++a) {
      std::uniform_real_distribution<double> u(lattice.wall(a, root.lo[a]) + 1e-3, lattice.wall(a, root.lo[a] + side) - 1e-3);
      p[std::size_t(a)] = float(u(rng));
    }
    return p;
  }

  Lattice lattice;
  Cell root;
};

TEST_F(LatticeTest, SidesHalveFromTheRootToOneUnit) {
  for (int d = 0; d <= lattice.max_depth; ++d) EXPECT_EQ(lattice.side(d), std::int64_t{1} << (lattice.max_depth - d));
  EXPECT_EQ(lattice.side(lattice.max_depth), 1);
}

TEST_F(LatticeTest, CellAtAgreesWithTheDescentForRandomPoints) {
  std::mt19937 rng(5);
  for (int i = 0; i < 20000; ++i) {
    const std::array<float, 3> p = random_point(rng);
    const std::vector<Cell> path = descent(p, lattice.max_depth);
    for (const Cell& c : path) {
      const Cell direct = lattice.cell_at(c.depth, p);
      ASSERT_EQ(direct.lo, c.lo) << "depth " << c.depth;
      ASSERT_TRUE(lattice.contains(c, p));
      ASSERT_TRUE(lattice.encloses(root, c));
      if (c.depth > 0) {
        const Cell& parent = path[std::size_t(c.depth - 1)];
        ASSERT_TRUE(lattice.encloses(parent, c));
        ASSERT_EQ(lattice.child(parent, lattice.octant_of(parent, c)).lo, c.lo);
      }
    }
  }
}

TEST_F(LatticeTest, APointOnAWallBelongsToTheCellAboveIt) {
  std::mt19937 rng(9);
  for (int i = 0; i < 5000; ++i) {
    std::array<float, 3> p = random_point(rng);
    const int axis = int(rng() % 3);
    const Cell leaf = lattice.cell_at(lattice.max_depth, p);
    // the float nearest the cell's lower wall on `axis`, and the float just below it
    const double wall = lattice.wall(axis, leaf.lo[std::size_t(axis)]);
    float on = float(wall);
    if (double(on) < wall) on = std::nextafter(on, 1e30F);  // the first float not below the wall
    p[std::size_t(axis)] = on;
    const Cell at = lattice.cell_at(lattice.max_depth, p);
    ASSERT_EQ(at.lo[std::size_t(axis)], leaf.lo[std::size_t(axis)]) << "on the wall: the cell above";
    ASSERT_EQ(descent(p, lattice.max_depth).back().lo, at.lo);
    if (leaf.lo[std::size_t(axis)] == root.lo[std::size_t(axis)]) continue;  // below is outside the root
    p[std::size_t(axis)] = std::nextafter(on, -1e30F);
    const Cell below = lattice.cell_at(lattice.max_depth, p);
    ASSERT_EQ(below.lo[std::size_t(axis)], leaf.lo[std::size_t(axis)] - 1) << "just below: the cell below";
    ASSERT_EQ(descent(p, lattice.max_depth).back().lo, below.lo);
  }
}

TEST_F(LatticeTest, ContainsIsHalfOpenAndBoundsNeedBothCorners) {
  const Cell c = lattice.child(root, 0);
  const std::int64_t s = lattice.side(1);
  auto at = [&](double x, double y, double z) {
    return std::array<float, 3>{float(x), float(y), float(z)};
  };
  const double x0 = lattice.wall(0, c.lo[0]), y0 = lattice.wall(1, c.lo[1]), z0 = lattice.wall(2, c.lo[2]);
  const double x1 = lattice.wall(0, c.lo[0] + s);
  EXPECT_TRUE(lattice.contains(c, at(x0 + 0.01, y0 + 0.01, z0 + 0.01)));
  EXPECT_FALSE(lattice.contains(c, at(x1 + 0.01, y0 + 0.01, z0 + 0.01)));
  Aabb inside;
  inside.grow(float(x0 + 0.01), float(y0 + 0.01), float(z0 + 0.01));
  EXPECT_TRUE(lattice.contains(c, inside));
  inside.grow(float(x1 + 0.5), float(y0 + 0.01), float(z0 + 0.01));
  EXPECT_FALSE(lattice.contains(c, inside));
}

}  // namespace
}  // namespace eco::detail
