// The method registry: names to makers.

#include "baselines/makers.hpp"

#include <algorithm>
#include <stdexcept>

namespace eco::baselines {

std::vector<Neighbor> Method::knn(const Eigen::Vector3d& query, std::size_t k) const {
  std::vector<Neighbor> out(std::min(k, size()));
  out.resize(knn(query, std::span<Neighbor>(out)));
  return out;
}

const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names{"eco",         "eco_exact",      "eco_clearing",   "eco_ball",
                                              "eco_box",     "octree_base",    "ioctree_global", "ioctree_target",
                                              "nanoflann",   "pcl_octree",     "scan_pass",      "scan_only"};
  return names;
}

std::unique_ptr<Method> make_method(std::string_view name, const Config& config) {
  if (name == "eco") return make_eco(config, Recentring::Quantised);
  if (name == "eco_exact") return make_eco(config, Recentring::Exact);
  if (name == "eco_clearing") return make_eco_clearing(config);
  if (name == "eco_ball") return make_eco_ball(config);
  if (name == "eco_box") return make_eco_box(config);
  const auto& names = method_names();
  const bool listed = std::find(names.begin(), names.end(), name) != names.end();
  if (listed && config.region.shape != RegionShape::Cube && name != "scan_only") {  // the Chamfer reference: the scan
    throw std::invalid_argument("method '" + std::string(name) + "' holds the cube only, not region.shape = " +
                                (config.region.shape == RegionShape::Ball ? "ball" : "oriented_box") +
                                ": compare regions with eco, eco_exact, eco_clearing, eco_ball and eco_box");
  }
  if (name == "octree_base") return make_octree_base(config);
  if (name == "ioctree_global") return make_ioctree_global(config);
  if (name == "ioctree_target") return make_ioctree_target(config);
  if (name == "nanoflann") return make_nanoflann(config);
  if (name == "pcl_octree") return make_pcl_octree(config);
  if (name == "scan_pass") return make_scan_pass(config);
  if (name == "scan_only") return make_scan_only(config);
  std::string known;
  for (const std::string& n : method_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown method '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace eco::baselines
