// eco.EgoOctree: the C++ EgoOctree behind a reader-writer lock, fed and read with numpy arrays;
// eco.Snapshot: one of its snapshots, with the same query methods. The GIL is released while C++
// works; the lock keeps update() and snapshot() exclusive of queries, as the C++ contract asks,
// when Python threads share a tree. A snapshot needs no lock: it never changes.

#include "bindings.hpp"
#include "config_record.hpp"

#include <eco/ego_octree.hpp>

#include <algorithm>
#include <limits>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

namespace eco::python {
namespace {

struct SharedTree {
  explicit SharedTree(const Config& config) : tree(config) {}
  explicit SharedTree(EgoOctree loaded) : tree(std::move(loaded)) {}
  EgoOctree tree;
  mutable std::shared_mutex mutex;
};

/// A snapshot as Python holds it.
struct SnapshotHandle {
  std::shared_ptr<const Snapshot> snapshot;
};

/// Runs `work(map)` (a const MapReader&) without the GIL, holding the tree's lock shared.
template <class Work>
auto reading(const SharedTree& t, Work&& work) {
  py::gil_scoped_release no_gil;
  std::shared_lock lock(t.mutex);
  return work(static_cast<const MapReader&>(t.tree));
}
/// The same for a snapshot, which needs no lock.
template <class Work>
auto reading(const SnapshotHandle& s, Work&& work) {
  py::gil_scoped_release no_gil;
  return work(static_cast<const MapReader&>(*s.snapshot));
}
template <class Work>
auto writing(SharedTree& t, Work&& work) {
  py::gil_scoped_release no_gil;
  std::unique_lock lock(t.mutex);
  return work(t.tree);
}

/// A binding that returns `(map.*getter)()` read as reading() reads, without the GIL.
template <class Holder, auto getter>
auto read() {
  return [](const Holder& self) {
    return reading(self, [](const auto& t) { return (t.*getter)(); });
  };
}

/// A scan's per-point attributes as update() takes them (None where not given).
struct AttributeArgs {
  py::object ids, intensities, times;
};

/// The C++ update names its pose argument world_T_sensor; say which Python argument it was.
template <class Work>
UpdateStats update_with(SharedTree& self, const char* pose_name, const Eigen::Isometry3d& pose,
                        const py::object& points, const AttributeArgs& attributes, Work&& work) {
  const Rows3 rows(points, "points", /*allow_single=*/false);
  const auto ids = column_arg<std::uint32_t>(attributes.ids, "ids", rows.size());
  const auto intensities = column_arg<float>(attributes.intensities, "intensities", rows.size());
  const auto times = column_arg<double>(attributes.times, "times", rows.size());
  std::vector<float> converted;
  ScanView scan = rows.scan(converted);
  scan.ids = attributes.ids.is_none() ? nullptr : ids.data();
  scan.intensities = attributes.intensities.is_none() ? nullptr : intensities.data();
  scan.times = attributes.times.is_none() ? nullptr : times.data();
  try {
    return writing(self, [&](EgoOctree& tree) { return work(tree, pose, scan); });
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    // name the Python argument: the C++ message names the pose argument or the scan's array
    const bool about_scan = what.find("scan.") != std::string::npos;
    throw py::value_error((about_scan ? std::string("scan") : std::string(pose_name)) +
                          " rejected (tree unchanged): " + what);
  }
}

/// k >= 1: one rule and one message for every value below (0, -1, ...), as the C++ tools say it.
std::size_t k_arg(const py::object& k) {
  const auto value = integer_arg<long long>(k, "k");
  if (value < 1) throw py::value_error("k = " + std::to_string(value) + " must be >= 1");
  return std::size_t(value);
}

/// Threads for a batch query: workers >= 1, or -1 for one per core (as scipy's `workers`).
unsigned workers_arg(const py::object& value) {
  const auto w = integer_arg<long long>(value, "workers");
  if (w == -1) return std::max(1u, std::thread::hardware_concurrency());
  if (w < 1) {
    throw py::value_error("workers = " + std::to_string(w) + " must be >= 1, or -1 for every core");
  }
  return unsigned(w);
}

/// Calls work(begin, end) on contiguous slices of [0, count), one thread per slice, the calling
/// thread taking the first; rethrows the first exception a slice threw once all have joined.
template <class Work>
void in_slices(std::size_t count, unsigned workers, const Work& work) {
  const std::size_t slices = std::clamp<std::size_t>(workers, 1, std::max<std::size_t>(count, 1));
  const std::size_t step = (count + slices - 1) / std::max<std::size_t>(slices, 1);
  std::vector<std::exception_ptr> errors(slices);
  const auto run = [&](std::size_t s) {
    try {
      work(std::min(count, s * step), std::min(count, (s + 1) * step));
    } catch (...) {
      errors[s] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t s = 1; s < slices; ++s) threads.emplace_back(run, s);
  run(0);
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

py::tuple neighbors_arrays(const std::vector<Neighbor>& found) {
  py::array_t<double> points({found.size(), std::size_t(3)});
  py::array_t<double> sq_dists(found.size());
  auto p = points.mutable_unchecked<2>();
  auto d = sq_dists.mutable_unchecked<1>();
  for (std::size_t i = 0; i < found.size(); ++i) {
    for (int c = 0; c < 3; ++c) p(py::ssize_t(i), c) = found[i].point[c];
    d(py::ssize_t(i)) = found[i].sq_dist;
  }
  return py::make_tuple(points, sq_dists);
}

/// The map's configuration (fixed for its life).
template <class Holder>
const Config& config_of(const Holder& self) {
  if constexpr (std::is_same_v<Holder, SharedTree>) {
    return self.tree.config();
  } else {
    return self.snapshot->config();
  }
}

/// Raises ValueError unless the tree keeps ids (what return_ids=True asks for).
template <class Holder>
void require_ids(const Holder& self) {
  if (!config_of(self).attributes.ids) {
    throw py::value_error("return_ids=True needs ids kept: config.attributes.ids is off");
  }
}

/// knn(..., return_ids=True): (sq_dists, ids), SciPy's (dists, idx) with squared distances.
template <class Holder>
py::tuple knn_ids(const Holder& self, const Rows3& q, std::size_t k, Frame frame, unsigned workers) {
  require_ids(self);
  const std::size_t m = q.size();
  std::vector<double> sq_dists;
  std::vector<std::uint32_t> ids;
  const std::size_t columns = reading(self, [&](const MapReader& tree) {
    const std::size_t kept = std::min(k, tree.size());
    sq_dists.resize(m * kept);
    ids.resize(m * kept);
    in_slices(m, workers, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        tree.knn(q.row(i), std::span(ids).subspan(i * kept, kept), std::span(sq_dists).subspan(i * kept, kept),
                 frame);
      }
    });
    return kept;
  });
  using Shape = std::vector<std::size_t>;
  const Shape shape = q.single() ? Shape{columns} : Shape{m, columns};
  return py::make_tuple(shaped_array(std::move(sq_dists), shape), shaped_array(std::move(ids), shape));
}

template <class Holder>
py::tuple knn(const Holder& self, const py::object& queries, const py::object& k_value,
              const py::object& frame_value, const py::object& workers_value, bool return_ids) {
  const Rows3 q(queries, "queries", /*allow_single=*/true);
  q.require_finite();
  const std::size_t k = k_arg(k_value);
  const Frame frame = enum_arg<Frame>(frame_value, "frame");
  const unsigned workers = workers_arg(workers_value);
  if (return_ids) return knn_ids(self, q, k, frame, workers);
  const std::size_t m = q.size();
  // k is clamped to the points held, so a huge k costs no more than the tree's size.
  std::vector<double> points, sq_dists;
  const std::size_t columns = reading(self, [&](const MapReader& tree) {
    const std::size_t kept = std::min(k, tree.size());
    points.resize(m * kept * 3);
    sq_dists.resize(m * kept);
    in_slices(m, workers, [&](std::size_t begin, std::size_t end) {
      std::vector<Neighbor> found(kept);
      for (std::size_t i = begin; i < end; ++i) {
        tree.knn(q.row(i), found, frame);  // finds all `kept`: every held point is a candidate
        for (std::size_t j = 0; j < kept; ++j) {
          for (int c = 0; c < 3; ++c) points[(i * kept + j) * 3 + std::size_t(c)] = found[j].point[c];
          sq_dists[i * kept + j] = found[j].sq_dist;
        }
      }
    });
    return kept;
  });
  using Shape = std::vector<std::size_t>;
  return py::make_tuple(shaped_array(std::move(points), q.single() ? Shape{columns, 3} : Shape{m, columns, 3}),
                        shaped_array(std::move(sq_dists), q.single() ? Shape{columns} : Shape{m, columns}));
}

/// radius(..., return_ids=True): (sq_dists, ids) of one query.
py::tuple distances_and_ids(const std::vector<Neighbor>& found) {
  std::vector<double> sq_dists;
  std::vector<std::uint32_t> ids;
  for (const Neighbor& n : found) {
    sq_dists.push_back(n.sq_dist);
    ids.push_back(n.attributes.id);
  }
  return py::make_tuple(values_array(std::move(sq_dists)), values_array(std::move(ids)));
}

template <class Holder>
py::object radius(const Holder& self, const py::object& queries, const py::object& radius_value,
                  const py::object& frame_value, const py::object& workers_value, bool return_ids) {
  const Rows3 q(queries, "queries", /*allow_single=*/true);
  q.require_finite();
  const double r = number_arg(radius_value, "radius");
  const Frame frame = enum_arg<Frame>(frame_value, "frame");
  const unsigned workers = workers_arg(workers_value);
  if (return_ids) require_ids(self);
  const auto as_arrays = return_ids ? &distances_and_ids : &neighbors_arrays;
  const auto found = reading(self, [&](const MapReader& tree) {
    std::vector<std::vector<Neighbor>> out(q.size());
    in_slices(q.size(), workers, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) out[i] = tree.radius(q.row(i), r, frame);
    });
    return out;
  });
  if (q.single()) return as_arrays(found.front());
  py::list out;
  for (const auto& one : found) out.append(as_arrays(one));
  return out;
}

/// (points, attributes) of held points: an (n, 3) array and a dict of the kept attributes'
/// (n,) arrays: "ids" uint32, "intensities" float32, "times" float64.
py::tuple with_attributes(const KeptAttributes& kept, const std::vector<HeldPoint>& held) {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::uint32_t> ids;
  std::vector<float> intensities;
  std::vector<double> times;
  points.reserve(held.size());
  for (const HeldPoint& h : held) {
    points.push_back(h.point);
    if (kept.ids) ids.push_back(h.attributes.id);
    if (kept.intensity) intensities.push_back(h.attributes.intensity);
    if (kept.time) times.push_back(h.attributes.time);
  }
  py::dict attributes;
  if (kept.ids) attributes["ids"] = values_array(std::move(ids));
  if (kept.intensity) attributes["intensities"] = values_array(std::move(intensities));
  if (kept.time) attributes["times"] = values_array(std::move(times));
  return py::make_tuple(rows_array(std::move(points)), attributes);
}

py::array_t<std::int64_t> keys_array(const std::vector<VoxelKey>& keys) {
  py::array_t<std::int64_t> out({keys.size(), std::size_t(3)});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    a(py::ssize_t(i), 0) = keys[i].x;
    a(py::ssize_t(i), 1) = keys[i].y;
    a(py::ssize_t(i), 2) = keys[i].z;
  }
  return out;
}

constexpr const char* kTreeDoc =
    R"(The Ego-Centric Octree: the points inside a cube of side L that travels with the sensor.

EgoOctree(config=None, **fields) takes a Config, or Config's fields as keyword arguments
(e.g. EgoOctree(box_side=30.0, insert_policy="AllInBox")); a bad value raises ValueError or
TypeError naming the field.

After update() the held points are exactly the previous ones plus the inserted ones, restricted
to the half-open box [p - L/2, p + L/2) (less density-cap refusals and aged points); queries are
exact over them. A rejected call raises and leaves the tree unchanged. The GIL is released
while C++ works; queries may run from several threads at once, updates run alone.

Array arguments: points and queries are (N, 3) array-likes of real numbers (numpy arrays of any
real dtype and layout, lists); C-contiguous float32 and float64 arrays are read in place, anything
else is converted first. Small arguments (poses, box corners) take the same. Results are float64 numpy arrays in the query's frame.)";

/// The query methods, alike on a tree and on a snapshot (Holder: SharedTree or SnapshotHandle).
template <class Holder>
void def_queries(py::class_<Holder>& cls) {
  cls.def("knn", &knn<Holder>, py::arg("queries"), py::arg("k"), py::arg("frame") = Frame::World,
           py::arg("workers") = 1, py::kw_only(), py::arg("return_ids") = false,
           R"(The k nearest held points to each query, nearest first, exact.

queries: (M, 3) float32/float64 array, or one (3,) point.
Returns (points, sq_dists): (M, n, 3) and (M, n) float64 arrays ((n, 3) and (n,) for one
point), n = min(k, len(tree)): k is clamped to the points held (SciPy pads with inf instead).
frame: Frame.World (default) or Frame.Ego (world axes, origin at the sensor), or its name.
workers: threads sharing the batch (default 1; -1: one per core). Answers do not depend on it.
return_ids: return (sq_dists, ids) instead, ids the uint32 ids given to update() (needs
    config.attributes.ids), in the shapes of sq_dists: scipy.spatial.cKDTree.query's (dists, idx)
    with squared distances and the caller's ids in place of row indices.)")
      .def("radius", &radius<Holder>, py::arg("queries"), py::arg("radius"),
           py::arg("frame") = Frame::World, py::arg("workers") = 1, py::kw_only(), py::arg("return_ids") = false,
           R"(Held points within `radius` metres (closed ball) of each query, nearest first.

For one (3,) query returns (points (n, 3), sq_dists (n,)); for (M, 3) queries, a list of M
such pairs. workers: as for knn(). return_ids: (sq_dists, ids) pairs instead, as for knn().)")
      .def(
          "box",
          [](const Holder& self, const py::object& lo_value, const py::object& hi_value,
             const py::object& frame_value, bool attributes) -> py::object {
            const Eigen::Vector3d lo = vector3_arg(lo_value, "lo");
            const Eigen::Vector3d hi = vector3_arg(hi_value, "hi");
            const Frame frame = enum_arg<Frame>(frame_value, "frame");
            if (attributes) {
              return with_attributes(config_of(self).attributes, reading(self, [&](const MapReader& t) {
                                       return t.box_with_attributes(lo, hi, frame);
                                     }));
            }
            return rows_array(
                reading(self, [&](const MapReader& t) { return t.box(lo, hi, frame); }));
          },
          py::arg("lo"), py::arg("hi"), py::arg("frame") = Frame::World, py::kw_only(),
          py::arg("attributes") = false,
          "Held points inside the closed box [lo, hi] (3-vectors), as an (n, 3) array in no "
          "particular order. attributes=True: (points, attributes), attributes a dict of the kept "
          "ones' (n,) arrays, in the points' order: 'ids' uint32, 'intensities' float32, 'times' float64.")
      .def(
          "oriented_box",
          [](const Holder& self, const py::object& pose_value, const py::object& lo_value, const py::object& hi_value,
             const py::object& frame_value, bool attributes) -> py::object {
            const Eigen::Isometry3d box_pose = pose_arg(pose_value, "box_pose");
            const Eigen::Vector3d lo = vector3_arg(lo_value, "lo");
            const Eigen::Vector3d hi = vector3_arg(hi_value, "hi");
            const Frame frame = enum_arg<Frame>(frame_value, "frame");
            if (attributes) {
              return with_attributes(config_of(self).attributes, reading(self, [&](const MapReader& t) {
                                       return t.oriented_box_with_attributes(box_pose, lo, hi, frame);
                                     }));
            }
            return rows_array(reading(self, [&](const MapReader& t) { return t.oriented_box(box_pose, lo, hi, frame); }));
          },
          py::arg("box_pose"), py::arg("lo"), py::arg("hi"), py::arg("frame") = Frame::World, py::kw_only(),
          py::arg("attributes") = false,
          "Held points inside the closed box [lo, hi] of the axes the 4x4 rigid `box_pose` places in "
          "`frame`, returned in `frame`: a box turned any way (what lies 2 m ahead of the bumper: "
          "box_pose = sensor_T_bumper, frame=Frame.Sensor). As box() otherwise.")
      .def(
          "voxelize",
          [](const Holder& self, const py::object& resolution, const py::object& frame_value) {
            const double res = number_arg(resolution, "resolution");
            const Frame frame = enum_arg<Frame>(frame_value, "frame");
            return rows_array(
                reading(self, [&](const MapReader& t) { return t.voxelize(res, frame); }));
          },
          py::arg("resolution"), py::arg("frame") = Frame::World,
          "Centres of the occupied voxels of the world-aligned grid of side `resolution` [m], "
          "as a (V, 3) array in key order.")
      .def(
          "voxel_keys",
          [](const Holder& self, const py::object& resolution) {
            const double res = number_arg(resolution, "resolution");
            return keys_array(reading(self, [&](const MapReader& t) { return t.voxel_keys(res); }));
          },
          py::arg("resolution"),
          "Integer keys (V, 3) int64 of the occupied voxels, unique, in no particular order (the "
          "tree's): voxel i spans [i*resolution, (i+1)*resolution) per axis. Fastest when "
          "resolution is config.voxel_size * 2^i (then nodes are visited, not points).")
      .def(
          "points",
          [](const Holder& self, bool attributes) -> py::object {
            if (attributes) {
              return with_attributes(config_of(self).attributes, read<Holder, &MapReader::points_with_attributes>()(self));
            }
            return rows_array(read<Holder, &MapReader::points>()(self));
          },
          py::kw_only(), py::arg("attributes") = false,
          "Every held point, world frame, as an (N, 3) float64 array in no particular order. "
          "attributes=True: (points, attributes) as box() gives them.")
      .def("stats", read<Holder, &MapReader::stats>(), "What the tree holds now (a Stats; O(nodes)).")
      .def("check_invariants", read<Holder, &MapReader::check_invariants>(),
           "Checks every structural invariant; returns '' when all hold, else the first violation.")
      .def("__len__", read<Holder, &MapReader::size>(), "Points held.")
      .def_property_readonly("size", read<Holder, &MapReader::size>(), "Points held, O(1).")
      .def_property_readonly(
          "config", [](const Holder& self) { return config_of(self); },
          "The tree's Config (a copy: a tree's configuration is fixed).")
      .def_property_readonly(
          "pose",
          [](const Holder& self) { return matrix_array(read<Holder, &MapReader::pose>()(self)); },
          "The current sensor pose world_T_sensor as a 4x4 array (identity before the first "
          "update).")
      .def_property_readonly(
          "ego_box",
          [](const Holder& self) -> py::object {
            const auto box = reading(self, [](const MapReader& t) { return t.ego_box(); });
            if (box.isEmpty()) return py::none();
            return py::make_tuple(vector_array(box.min()), vector_array(box.max()));
          },
          "The current ego box (lo, hi), world frame, half-open; None before the first update.")
      .def_property_readonly(
          "precision_origin",
          [](const Holder& self) {
            return vector_array(read<Holder, &MapReader::precision_origin>()(self));
          },
          "The world point that stored float coordinates are offsets from (a multiple of 1024 m).")
      .def_property_readonly("time_origin", read<Holder, &MapReader::time_origin>(),
                             "The time [s] stored times are offsets from (config.attributes.time; a multiple "
                             "of 64 s within 128 s of the latest time taken in; 0 before any).")
      .def_property_readonly("frame_count", read<Holder, &MapReader::frame_count>(),
                             "Updates taken so far.");
}

constexpr const char* kSnapshotDoc =
    R"(The map as it was when EgoOctree.snapshot() published it: the tree's query methods, with the
same names, arguments and results, answering as the tree did at that frame whatever it does after
(frame_count and pose name the frame). It never changes, so any number of Python threads may
query it at once, without the GIL and without waiting for the tree's updates. What only snapshots
hold (stats().snapshot_bytes) is given back when the last reference goes.)";

}  // namespace

void bind_tree(py::module_& m) {
  py::class_<SharedTree> tree(m, "EgoOctree", kTreeDoc);
  tree.def(py::init([](const py::object& config, const py::kwargs& fields) {
             return std::make_unique<SharedTree>(
                 config_or_fields<Config>(config, fields, "EgoOctree"));
           }),
           py::arg("config") = py::none(),
           "Creates an empty tree from a Config (or a dict of its fields) or keyword fields.")
      .def(
          "update",
          [](SharedTree& self, const py::object& pose, const py::object& points, const py::object& ids,
             const py::object& intensities, const py::object& times) {
            return update_with(self, "pose", pose_arg(pose, "pose"), points, {ids, intensities, times},
                               [](EgoOctree& t, const Eigen::Isometry3d& p, ScanView s) {
                                 return t.update(p, s);
                               });
          },
          py::arg("pose"), py::arg("points"), py::kw_only(), py::arg("ids") = py::none(),
          py::arg("intensities") = py::none(), py::arg("times") = py::none(),
          R"(Advances to the sensor pose and takes in a scan.

pose: 4x4 (or 3x4) world_T_sensor, mapping sensor-frame points to the world.
points: (N, 3) array-like, sensor frame; a C-contiguous float32 array is read in place, anything
    else converted. Coordinates are rounded to float32 (ECO stores float offsets). NaN/inf rows are skipped and counted, not raised on.
ids, intensities, times: optional per-point attributes, (N,) each: uint32 ids (any integer dtype,
    values in [0, 2^32)), float32 intensities, float64 times in seconds (finite, >= 0). The tree
    stores those config.attributes keeps (a kept one must be given) and ignores the others.
Returns the UpdateStats of this frame. A non-finite pose or a rotation that is not orthonormal,
an attribute of the wrong length or dtype, or a negative or non-finite time raises (ValueError or
TypeError naming the argument) and leaves the tree unchanged.)")
      .def(
          "update_relative",
          [](SharedTree& self, const py::object& motion, const py::object& points, const py::object& ids,
             const py::object& intensities, const py::object& times) {
            return update_with(self, "motion", pose_arg(motion, "motion"), points, {ids, intensities, times},
                               [](EgoOctree& t, const Eigen::Isometry3d& p, ScanView s) {
                                 return t.update_relative(p, s);
                               });
          },
          py::arg("motion"), py::arg("points"), py::kw_only(), py::arg("ids") = py::none(),
          py::arg("intensities") = py::none(), py::arg("times") = py::none(),
          R"(update() with the relative motion previous_T_current (4x4 or 3x4): the new sensor
pose expressed in the previous sensor frame. The first frame starts from the identity pose.
ids, intensities, times: as for update().)")
      .def(
          "save",
          [](const SharedTree& self, const py::object& path) {
            const std::string file = py::str(py::module_::import("os").attr("fspath")(path));
            py::gil_scoped_release no_gil;
            const std::shared_lock lock(self.mutex);
            self.tree.save(file);
          },
          py::arg("path"),
          "Writes the whole map (configuration, pose, origins, frame counter and clock, the held "
          "points with their attributes, clearing's state) to path (str or os.PathLike; "
          "docs/map-format.md), by way of a temporary file renamed over it: a save that fails leaves "
          "an earlier file at path as it was. Raises RuntimeError naming the path and the reason.")
      .def_static(
          "load",
          [](const py::object& path) {
            const std::string file = py::str(py::module_::import("os").attr("fspath")(path));
            py::gil_scoped_release no_gil;
            return std::make_unique<SharedTree>(EgoOctree::load(file));
          },
          py::arg("path"),
          "The map saved at path: it answers as the saved tree did and, fed the same next frames, "
          "stays identical to it. Raises RuntimeError naming the path and the byte offset of what "
          "is not a map (wrong magic or version, checksum mismatch, truncated file); nothing is "
          "loaded.")
      .def_property_readonly(
          "last_update",
          [](const SharedTree& self) {
            py::gil_scoped_release no_gil;
            const std::shared_lock lock(self.mutex);
            return UpdateStats(self.tree.last_update());
          },
          "The UpdateStats of the last update.")
      .def(
          "snapshot",
          [](SharedTree& self) {
            py::gil_scoped_release no_gil;
            const std::unique_lock lock(self.mutex);
            return SnapshotHandle{self.tree.snapshot()};
          },
          "An immutable Snapshot of the map as it is now, for readers on other threads: it answers "
          "every query as the tree does now, whatever the tree does after. It costs a reference per "
          "page of points (4-16 KiB) and a copy of the nodes, not a copy of the map.")
      .def("__repr__", [](const SharedTree& self) {
        const auto [points, frames] =
            reading(self, [](const MapReader& t) { return std::pair(t.size(), t.frame_count()); });
        return "EgoOctree(points=" + std::to_string(points) + ", frames=" + std::to_string(frames) +
               ", box_side=" + std::string(py::repr(py::float_(self.tree.config().box_side))) + ")";
      });
  def_queries(tree);

  py::class_<SnapshotHandle> snapshot(m, "Snapshot", kSnapshotDoc);
  def_queries(snapshot);
  snapshot.def("__repr__", [](const SnapshotHandle& self) {
    return "Snapshot(points=" + std::to_string(self.snapshot->size()) +
           ", frame=" + std::to_string(self.snapshot->frame_count()) + ")";
  });
}

}  // namespace eco::python
