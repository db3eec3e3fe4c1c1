// Admission::for_each, whose scan points are judged in vector code (src/update/admission.cpp),
// against the rule written out point by point with Eigen and Box::contains: the same points, with
// the same stored coordinates to the bit and the same scan indices, in scan order, and the same
// counts of non-finite and refused points — for random poses far from the world's origin, points
// on and beside the boxes' walls, non-finite coordinates, ShiftInOnly's previous box, scans of
// every stride and of lengths around a group's.

#include "update/admission.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace eco::detail {
namespace {

struct Taken {
  std::array<float, 3> p;
  std::size_t index;
  friend bool operator==(const Taken&, const Taken&) = default;
};

struct Verdicts {
  std::vector<Taken> taken;
  std::size_t nonfinite = 0, refused = 0;
};

/// The rule, one point after another: world = R·s + t by Eigen, minus the anchor, rounded once.
Verdicts by_the_rule(const Admission& a, ScanView scan) {
  Verdicts v;
  for (std::size_t i = 0; i < scan.count; ++i) {
    const Eigen::Vector3f s = scan[i];
    if (!s.allFinite()) {
      ++v.nonfinite;
      continue;
    }
    const Eigen::Matrix3d r = a.pose.linear();
    const Eigen::Vector3d w = r * s.cast<double>() + a.pose.translation();
    const std::array<float, 3> p{float(w[0] - a.anchor[0]), float(w[1] - a.anchor[1]), float(w[2] - a.anchor[2])};
    if (a.box.contains(p[0], p[1], p[2]) && !(a.previous && a.previous->contains(p[0], p[1], p[2]))) {
      v.taken.push_back({p, i});
    } else {
      ++v.refused;
    }
  }
  return v;
}

Verdicts admitted(const Admission& a, ScanView scan) {
  Verdicts v;
  UpdateStats stats;
  a.for_each(scan, stats, [&](const std::array<float, 3>& p, std::size_t i) { v.taken.push_back({p, i}); });
  v.nonfinite = stats.skipped_nonfinite;
  v.refused = stats.skipped_by_policy;
  return v;
}

void expect_same(const Verdicts& got, const Verdicts& want) {
  EXPECT_EQ(got.nonfinite, want.nonfinite);
  EXPECT_EQ(got.refused, want.refused);
  ASSERT_EQ(got.taken.size(), want.taken.size());
  for (std::size_t j = 0; j < want.taken.size(); ++j) {
    ASSERT_EQ(got.taken[j], want.taken[j]) << "admitted point " << j << " (scan index " << want.taken[j].index << ")";
  }
}

Box box_around(const Eigen::Vector3d& centre, double side) {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = centre[a] - side / 2;
    b.hi[a] = b.lo[a] + side;
  }
  return b;
}

/// Floats `stride` apart: the points, then padding the admission must not read as coordinates.
std::vector<float> laid_out(const std::vector<Eigen::Vector3f>& points, std::size_t stride) {
  std::vector<float> data(points.size() * stride, -7.5e30f);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) data[i * stride + std::size_t(a)] = points[i][a];
  }
  return data;
}

TEST(Admission, RandomPosesFarOutAreTheRules) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<float> reach(-30.0f, 30.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (int trial = 0; trial < 60; ++trial) {
    Admission a;
    a.pose.setIdentity();
    a.pose.linear() = Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized().toRotationMatrix();
    const double far = trial % 3 == 0 ? 3e6 : 2e3;  // far from the world's origin, and near it
    a.pose.translation() = Eigen::Vector3d(unit(rng) * far, unit(rng) * far, unit(rng) * 50.0);
    a.anchor = (a.pose.translation() / 1024.0).array().round() * 1024.0;
    const Eigen::Vector3d centre = a.pose.translation() - a.anchor;
    a.box = box_around(centre, 20.0);
    if (trial % 2 == 1) a.previous = box_around(centre - Eigen::Vector3d(unit(rng), unit(rng), 0.1) * 3.0, 20.0);
    const std::size_t n = std::size_t(trial) * 7 % 300;  // 0, 7, ..., around and across groups
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3f s(reach(rng), reach(rng), reach(rng) / 3.0f);
      if (i % 37 == 5) s[int(i % 3)] = i % 2 == 0 ? nan : -inf;
      points.push_back(s);
    }
    for (std::size_t stride : {3u, 4u, 5u}) {
      const std::vector<float> data = laid_out(points, stride);
      const ScanView scan(data.data(), n, stride);
      SCOPED_TRACE(testing::Message() << "trial " << trial << ", stride " << stride);
      expect_same(admitted(a, scan), by_the_rule(a, scan));
    }
  }
}

TEST(Admission, EachRowSummedAsEigenSumsIt) {
  // A row's two summing orders differ by an ulp of the double now and then, which changes the
  // stored float only when the sum lies on a midpoint between floats; the translation puts
  // Eigen's sum there (t = m - sum is exact for sums and midpoints in [4, 8)), where the other
  // order rounds to the other float.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int row = 0; row < 3; ++row) {
    for (int found = 0; found < 8;) {
      const Eigen::Matrix3d r =
          Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized().toRotationMatrix();
      const Eigen::Vector3f s(float(unit(rng) * 8), float(unit(rng) * 8), float(unit(rng) * 8));
      const Eigen::Vector3d d = s.cast<double>();
      const double eigen = (r * d)[row];
      const double left_first = (r(row, 0) * d[0] + r(row, 1) * d[1]) + r(row, 2) * d[2];
      const double right_first = r(row, 0) * d[0] + (r(row, 1) * d[1] + r(row, 2) * d[2]);
      const double other = eigen == left_first ? right_first : left_first;
      if (!(eigen >= 4.0 && eigen < 8.0) || other == eigen) continue;
      const double midpoint = (2.0 * std::floor(eigen * 0x1p21) + 1.0) * 0x1p-22;
      Eigen::Vector3d t = Eigen::Vector3d::Zero();
      t[row] = midpoint - eigen;
      if (float(eigen + t[row]) == float(other + t[row])) continue;  // the other order rounds alike here
      ++found;
      Admission a;
      a.pose.setIdentity();
      a.pose.linear() = r;
      a.pose.translation() = t;
      a.anchor.setZero();
      a.box = box_around(Eigen::Vector3d::Zero(), 40.0);
      const std::vector<Eigen::Vector3f> points{s};
      const Verdicts want = by_the_rule(a, ScanView(points));
      ASSERT_EQ(want.taken.size(), 1u);
      ASSERT_EQ(want.taken[0].p[std::size_t(row)], float(midpoint));
      SCOPED_TRACE(testing::Message() << "row " << row << ", case " << found);
      expect_same(admitted(a, ScanView(points)), want);
    }
  }
}

TEST(Admission, PointsOnAndBesideTheWalls) {
  // the identity pose and a zero anchor store a scan point as it is, so the scan can put points on
  // the walls' floats and their neighbours; walls that floats hold exactly and walls between floats
  const float up = std::numeric_limits<float>::infinity(), down = -up;
  for (const bool half_open : {true, false}) {
    for (const double side : {2.0, 0.1}) {
      Admission a;
      a.pose.setIdentity();
      a.anchor.setZero();
      a.box = box_around(Eigen::Vector3d(0.3, -1.0, 0.7), side);
      a.box.half_open = half_open;
      Box previous = box_around(Eigen::Vector3d(0.3 + side / 3, -1.0, 0.7), side);
      previous.half_open = half_open;
      for (const bool shift_in : {false, true}) {
        a.previous = shift_in ? std::optional<Box>(previous) : std::nullopt;
        std::vector<Eigen::Vector3f> points;
        for (int axis = 0; axis < 3; ++axis) {
          for (const double wall : {a.box.lo[axis], a.box.hi[axis], previous.lo[axis], previous.hi[axis]}) {
            const float at = float(wall);
            for (const float f : {std::nextafter(at, down), at, std::nextafter(at, up)}) {
              Eigen::Vector3f s(0.3f, -1.0f, 0.7f);
              s[axis] = f;
              points.push_back(s);
            }
          }
        }
        const ScanView scan(points);
        SCOPED_TRACE(testing::Message() << "half-open " << half_open << ", side " << side << ", shift-in " << shift_in);
        const Verdicts want = by_the_rule(a, scan);
        EXPECT_GT(want.taken.size(), 0u);
        EXPECT_GT(want.refused, 0u);
        expect_same(admitted(a, scan), want);
      }
    }
  }
}

}  // namespace
}  // namespace eco::detail
