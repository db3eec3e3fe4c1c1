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
  s.first_update_ms = run.frames.front().update_ms;
  const std::size_t skip = run.frames.size() > 1 ? 1 : 0;  // time the updates, not the first build
  for (std::size_t i = skip; i < run.frames.size(); ++i) {
    const FrameRecord& r = run.frames[i];
    updates.push_back(r.update_ms);
    s.update_ms += r.update_ms;
    s.update_faults += double(r.update_faults);
    s.caller_ms += r.caller_ms;
    s.caller_faults += double(r.caller_faults);
    s.voxel_ms += r.voxel_ms;
    s.knn_ms += r.knn_ms;
    s.region_tested += double(r.region_tested);
  }
  for (const FrameRecord& r : run.frames) {
    s.points += double(r.points);
    s.nodes += double(r.nodes);
    s.mean_depth += r.mean_depth;
    s.max_depth = std::max(s.max_depth, r.max_depth);
    s.bytes = std::max(s.bytes, r.bytes);
    s.chamfer_m += r.chamfer_m;
    s.region_scale_min = std::min(s.region_scale_min, r.region_scale);
    s.frames_over_budget += r.over_budget ? 1 : 0;
    if (r.points > 0) {
      s.bytes_per_point += double(r.bytes) / double(r.points);
      ++holding;
    }
  }
  const double n = double(run.frames.size());
  for (double* v : {&s.points, &s.nodes, &s.mean_depth, &s.chamfer_m}) *v /= n;
  const double timed = double(updates.size());
  for (double* v : {&s.update_ms, &s.update_faults, &s.caller_ms, &s.caller_faults, &s.voxel_ms, &s.knn_ms, &s.region_tested}) {
    *v /= timed;
  }
  s.bytes_per_point = holding > 0 ? s.bytes_per_point / double(holding) : 0.0;
  std::sort(updates.begin(), updates.end());
  const auto rank = std::size_t(std::ceil(0.99 * timed));  // nearest-rank percentile
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
