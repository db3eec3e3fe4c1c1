#include "bench/summary.hpp"

#include <algorithm>
#include <cmath>

namespace eco::bench {

MethodSummary summarize(const MethodRun& run) {
  MethodSummary s;
  s.name = run.name;
  s.frames = run.frames.size();
  if (run.frames.empty()) return s;
  std::vector<double> updates;
  std::size_t holding = 0;
  for (const FrameRecord& r : run.frames) {
    updates.push_back(r.update_ms);
    s.update_ms += r.update_ms;
    s.voxel_ms += r.voxel_ms;
    s.knn_ms += r.knn_ms;
    s.points += double(r.points);
    s.nodes += double(r.nodes);
    s.mean_depth += r.mean_depth;
    s.max_depth = std::max(s.max_depth, r.max_depth);
    s.bytes = std::max(s.bytes, r.bytes);
    s.chamfer_m += r.chamfer_m;
    if (r.points > 0) {
      s.bytes_per_point += double(r.bytes) / double(r.points);
      ++holding;
    }
  }
  const double n = double(run.frames.size());
  for (double* v : {&s.update_ms, &s.voxel_ms, &s.knn_ms, &s.points, &s.nodes, &s.mean_depth, &s.chamfer_m}) {
    *v /= n;
  }
  s.bytes_per_point = holding > 0 ? s.bytes_per_point / double(holding) : 0.0;
  std::sort(updates.begin(), updates.end());
  const auto rank = std::size_t(std::ceil(0.99 * n));  // nearest-rank percentile
  s.update_ms_p99 = updates[std::min(updates.size(), std::max<std::size_t>(rank, 1)) - 1];
  s.first_depth = run.frames.front().mean_depth;
  s.last_depth = run.frames.back().mean_depth;
  return s;
}

std::vector<MethodSummary> summarize(const BenchRun& run) {
  std::vector<MethodSummary> out;
  for (const MethodRun& m : run.methods) out.push_back(summarize(m));
  return out;
}

}  // namespace eco::bench
