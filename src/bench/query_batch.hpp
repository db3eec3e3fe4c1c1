#pragma once
// The KNN queries of one frame, the same for every method: input points of the frame that fall
// in the ego box, jittered by a few centimetres (a registration step's queries: near the map's
// surfaces, not on its points). Drawn from a fixed seed per frame.

#include <eco/workloads/workload.hpp>

#include <cstdint>
#include <vector>

namespace eco::bench {

std::vector<Eigen::Vector3d> make_queries(const workloads::WorkloadFrame& frame, double box_side, std::size_t count,
                                          std::uint64_t seed);

}  // namespace eco::bench
