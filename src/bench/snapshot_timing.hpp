#pragma once
// What publishing snapshots costs (EgoOctree::snapshot()), measured on the run's own frames: three
// trees take every frame side by side: one alone; one publishing a snapshot after each update and
// holding it a frame more while a reader thread queries the latest one without pause; and one that
// never publishes, updated while that reader runs (what a reader costs any work on this machine).

#include "bench/bench_options.hpp"

#include <cstddef>
#include <functional>
#include <string>

namespace eco::bench {

/// Means per frame, the first frame left out.
struct SnapshotTiming {
  double update_alone_ms = 0.0;       ///< the tree that never publishes
  double update_read_ms = 0.0;        ///< the publishing tree, a reader querying its last snapshot meanwhile
  double update_beside_ms = 0.0;      ///< a tree that never publishes, updated while the reader runs
  double publish_ms = 0.0;            ///< snapshot(), and letting go of the one a frame older
  double knn_live_ms = 0.0;           ///< the frame's query batch on the publishing tree
  double knn_snapshot_ms = 0.0;       ///< the same batch on the snapshot it just published
  double bytes_alone = 0.0;           ///< Stats::bytes of the tree that never publishes
  double bytes_with_snapshot = 0.0;   ///< the publishing tree's bytes and snapshot_bytes, last frame's snapshot held
  std::size_t reader_queries = 0;     ///< KNN queries the reader answered, in all
  std::size_t frames = 0;
};

/// Runs `options`' frames (options.config, options.knn_queries) through the two trees.
[[nodiscard]] SnapshotTiming time_snapshots(const BenchOptions& options,
                                            const std::function<void(const std::string&)>& status);

}  // namespace eco::bench
