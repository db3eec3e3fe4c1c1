// The queries of a held map, for the live tree and its snapshots alike (src/query does the work).

#include "core/tree/invariants.hpp"
#include "core/tree/tree.hpp"
#include "query/queries.hpp"

#include <eco/map_reader.hpp>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>

namespace eco {

std::size_t MapReader::size() const { return held().size(); }

const Config& MapReader::config() const { return held().config(); }
const Eigen::Isometry3d& MapReader::pose() const { return held().motion().pose; }
std::uint32_t MapReader::frame_count() const { return held().motion().frame; }
Eigen::Vector3d MapReader::precision_origin() const { return held().motion().anchor; }
double MapReader::time_origin() const { return held().motion().clock.seconds(0.0f); }

Eigen::AlignedBox3d MapReader::ego_box() const {
  if (held().motion().frame == 0) return Eigen::AlignedBox3d();  // empty
  const detail::Box b = held().motion().box;
  const Eigen::Vector3d anchor = held().motion().anchor;
  return {Eigen::Vector3d(b.lo[0], b.lo[1], b.lo[2]) + anchor, Eigen::Vector3d(b.hi[0], b.hi[1], b.hi[2]) + anchor};
}

void MapReader::for_each_point(const std::function<void(const Eigen::Vector3d&)>& visit) const {
  detail::for_each_held(held(), visit);
}

void MapReader::copy_points(std::span<float> xyz, const Eigen::Vector3d& origin) const {
  if (xyz.size() != 3 * size()) {
    throw std::invalid_argument("copy_points: " + std::to_string(xyz.size()) + " floats for " + std::to_string(size()) +
                                " points (3 a point)");
  }
  detail::copy_held(held(), origin, xyz.data());
}

std::vector<Eigen::Vector3d> MapReader::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(size());
  for_each_point([&](const Eigen::Vector3d& p) { out.push_back(p); });
  return out;
}

std::vector<HeldPoint> MapReader::points_with_attributes() const { return detail::held_points(held()); }

Stats MapReader::stats() const {
  Stats s = detail::tree_stats(held());
  s.bytes += bytes_beside_tree();
  return s;
}

std::size_t MapReader::knn(const Eigen::Vector3d& query, std::span<Neighbor> out, Frame frame) const {
  return detail::knn_query(held(), query, out, frame);
}

std::vector<Neighbor> MapReader::knn(const Eigen::Vector3d& query, std::size_t k, Frame frame) const {
  std::vector<Neighbor> out(std::min<std::size_t>(k, size()));
  out.resize(knn(query, std::span<Neighbor>(out), frame));
  return out;
}

std::size_t MapReader::knn(const Eigen::Vector3d& query, std::span<std::uint32_t> ids, std::span<double> sq_dists,
                          Frame frame) const {
  return detail::knn_ids_query(held(), query, ids, sq_dists, frame);
}

namespace {

constexpr std::size_t kChunk = 64;  // queries a thread takes at a time from a batch

void refuse_batch(const std::string& what) { throw std::invalid_argument("eco::knn (batch): " + what); }

void check_batch(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
                 std::span<std::size_t> found) {
  if (k == 0) refuse_batch("k = 0 must be >= 1");
  if (out.size() != queries.size() * k) {
    refuse_batch("out.size() = " + std::to_string(out.size()) + " must be queries.size() * k = " +
                 std::to_string(queries.size() * k));
  }
  if (found.size() != queries.size()) {
    refuse_batch("found.size() = " + std::to_string(found.size()) + " must be queries.size() = " +
                 std::to_string(queries.size()));
  }
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (!queries[i].allFinite()) refuse_batch("queries[" + std::to_string(i) + "] is not finite");
  }
}

}  // namespace

void MapReader::knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
                    std::span<std::size_t> found, unsigned threads, Frame frame) const {
  if (threads == 0) refuse_batch("threads = 0 must be >= 1");
  check_batch(queries, k, out, found);
  // no more threads than chunks: a helper with nothing to do would only cost its start
  QueryThreads pool(unsigned(std::clamp<std::size_t>((queries.size() + kChunk - 1) / kChunk, 1, threads)));
  knn(queries, k, out, found, pool, frame);
}

void MapReader::knn(std::span<const Eigen::Vector3d> queries, std::size_t k, std::span<Neighbor> out,
                    std::span<std::size_t> found, QueryThreads& threads, Frame frame) const {
  check_batch(queries, k, out, found);
  // chunks handed out as threads ask, so that a slower part of the batch does not hold one back
  std::atomic<std::size_t> next{0};
  threads.run([&] {
    for (std::size_t begin = next.fetch_add(kChunk); begin < queries.size(); begin = next.fetch_add(kChunk)) {
      const std::size_t end = std::min(queries.size(), begin + kChunk);
      for (std::size_t i = begin; i < end; ++i) found[i] = knn(queries[i], out.subspan(i * k, k), frame);
    }
  });
}

std::vector<Neighbor> MapReader::radius(const Eigen::Vector3d& query, double radius, Frame frame) const {
  return detail::radius_query(held(), query, radius, frame);
}

std::vector<Eigen::Vector3d> MapReader::box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Frame frame) const {
  return detail::box_query(held(), Eigen::Isometry3d::Identity(), lo, hi, frame);
}

std::vector<HeldPoint> MapReader::box_with_attributes(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                                     Frame frame) const {
  return detail::box_held_query(held(), Eigen::Isometry3d::Identity(), lo, hi, frame);
}

std::vector<Eigen::Vector3d> MapReader::oriented_box(const Eigen::Isometry3d& box_pose, const Eigen::Vector3d& lo,
                                                     const Eigen::Vector3d& hi, Frame frame) const {
  return detail::box_query(held(), box_pose, lo, hi, frame);
}

std::vector<HeldPoint> MapReader::oriented_box_with_attributes(const Eigen::Isometry3d& box_pose,
                                                               const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                                               Frame frame) const {
  return detail::box_held_query(held(), box_pose, lo, hi, frame);
}

std::vector<VoxelKey> MapReader::voxel_keys(double resolution) const {
  return detail::voxel_keys_of(held(), resolution);
}

std::vector<Eigen::Vector3d> MapReader::voxelize(double resolution, Frame frame) const {
  const std::vector<VoxelKey> keys = voxel_keys(resolution);
  const Eigen::Vector3d shift = frame == Frame::World ? Eigen::Vector3d::Zero() : Eigen::Vector3d(pose().translation());
  const Eigen::Matrix3d turn = frame == Frame::Sensor ? Eigen::Matrix3d(pose().linear().transpose())
                                                      : Eigen::Matrix3d::Identity();
  std::vector<Eigen::Vector3d> centres;
  centres.reserve(keys.size());
  for (const VoxelKey& k : keys) {
    const Eigen::Vector3d centre((double(k.x) + 0.5) * resolution, (double(k.y) + 0.5) * resolution,
                                 (double(k.z) + 0.5) * resolution);
    centres.push_back(frame == Frame::Sensor ? Eigen::Vector3d(turn * (centre - shift)) : Eigen::Vector3d(centre - shift));
  }
  return centres;
}

std::string MapReader::check_invariants() const { return detail::check_tree(held()); }

}  // namespace eco
