#include "bench/query_batch.hpp"

#include <random>

namespace eco::bench {

std::vector<Eigen::Vector3d> make_queries(const workloads::WorkloadFrame& frame, double box_side, std::size_t count,
                                          std::uint64_t seed) {
  std::mt19937_64 rng(seed * 1000003u + frame.index);
  std::normal_distribution<double> jitter(0.0, 0.05);
  std::uniform_real_distribution<double> anywhere(-box_side / 2, box_side / 2);
  const Eigen::Vector3d centre = frame.world_T_sensor.translation();
  std::vector<Eigen::Vector3d> queries;
  queries.reserve(count);
  const std::size_t n = frame.points.size();
  for (std::size_t tries = 0; queries.size() < count && tries < 20 * count && n > 0; ++tries) {
    const Eigen::Vector3f& p = frame.points[std::size_t(rng() % n)];
    if (!p.allFinite()) continue;
    const Eigen::Vector3d q = frame.world_T_sensor * p.cast<double>() + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    if (((q - centre).cwiseAbs().array() < box_side / 2).all()) queries.push_back(q);
  }
  while (queries.size() < count) queries.push_back(centre + Eigen::Vector3d(anywhere(rng), anywhere(rng), anywhere(rng)));
  return queries;
}

}  // namespace eco::bench
