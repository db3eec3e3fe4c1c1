#include "core/geometry/update_arguments.hpp"

#include "core/geometry/geometry.hpp"
#include "core/geometry/motion.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace eco::detail {
namespace {

/// How many quanta from the world origin a pose may lie in Quantised mode: the root cell's
/// integer lattice indices (a quantum is 2^(depth - k) of them, at most 2^23) stay far from
/// overflowing within it (7.9e11 m at the default quantum).
constexpr double kMaxQuanta = 0x1p38;

/// The most points a scan may hold: the update names them by 32-bit indices.
constexpr std::size_t kMaxScanPoints = std::numeric_limits<std::uint32_t>::max();

/// A kept attribute must come with every non-empty scan.
void require_attribute(const void* values, bool kept, const char* name, const char* field, std::size_t count) {
  if (kept && count > 0 && values == nullptr) {
    throw std::invalid_argument(std::string("eco::EgoOctree: scan.") + name + " is null but Config::" + field +
                                " is on (a kept attribute must come with every point of the scan's " +
                                std::to_string(count) + ")");
  }
}

void check_scan(const ScanView& scan, const Config& config) {
  if (scan.count > kMaxScanPoints) {  // scan indices are 32-bit through the update
    throw std::invalid_argument("eco::EgoOctree: scan.count = " + std::to_string(scan.count) + " exceeds " +
                                std::to_string(kMaxScanPoints) + " points");
  }
  if (scan.count > 0 && scan.data == nullptr) {
    throw std::invalid_argument("eco::EgoOctree: scan.data is null but scan.count = " +
                                std::to_string(scan.count));
  }
  if (scan.stride < 3) {
    throw std::invalid_argument("eco::EgoOctree: scan.stride = " + std::to_string(scan.stride) +
                                " is below 3 floats per point");
  }
  require_attribute(scan.ids, config.attributes.ids, "ids", "attributes.ids", scan.count);
  require_attribute(scan.intensities, config.attributes.intensity, "intensities", "attributes.intensity", scan.count);
  require_attribute(scan.times, config.attributes.time, "times", "attributes.time", scan.count);
  if (!config.attributes.time) return;
  for (std::size_t i = 0; i < scan.count; ++i) {
    if (!std::isfinite(scan.times[i]) || scan.times[i] < 0.0) {
      std::ostringstream s;
      s << "eco::EgoOctree: scan.times[" << i << "] = " << scan.times[i] << " s must be finite and >= 0";
      throw std::invalid_argument(s.str());
    }
  }
}

/// Density cells are named by 64-bit grid indices: refuse a pose so far out that they overflow.
void check_density_grid(const Eigen::Isometry3d& pose, const Config& config) {
  if (!config.density_cap.enabled()) return;
  const double reach = pose.translation().cwiseAbs().maxCoeff() + config.box_side;
  if (!grid_fits(reach, config.density_cap.cell_size)) {
    std::ostringstream s;
    s << "eco::EgoOctree: density_cap.cell_size = " << config.density_cap.cell_size
      << " m cannot index points " << reach << " m from the world origin (more than 2^50 cells)";
    throw std::invalid_argument(s.str());
  }
}

}  // namespace

void check_update_arguments(const Eigen::Isometry3d& pose, const char* name,
                                    const ScanView& scan, const Config& config) {
  check_pose(pose, name);
  // the quantum is at least box_side / (2^k - 1): only a pose past that bound computes it
  const double reach = pose.translation().cwiseAbs().maxCoeff();
  const double least_quantum = config.box_side / double((1u << config.quantum_levels) - 1u);
  if (config.recentring == Recentring::Quantised && !(reach < kMaxQuanta * least_quantum) &&
      !(reach < kMaxQuanta * config.quantum())) {
    throw std::invalid_argument(std::string("eco::EgoOctree: ") + name + " = " + describe_pose(pose) +
                                " lies farther than 2^38 quanta (q = " + std::to_string(config.quantum()) +
                                " m) from the world origin");
  }
  check_scan(scan, config);
  check_density_grid(pose, config);
}

}  // namespace eco::detail
