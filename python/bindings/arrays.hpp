#pragma once
// numpy arguments in, numpy results out. Every check names the Python argument it rejects:
// TypeError for the wrong kind of object or dtype, ValueError for a wrong shape or a non-finite
// value. Array-likes of any real dtype and layout are converted when needed, as numpy and SciPy do.

#include <eco/types.hpp>

#include <Eigen/Geometry>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <vector>

namespace eco::python {

namespace py = pybind11;

/// An (N, 3) array-like of real coordinates (any dtype, any strides), checked and held for the
/// duration of a call; or, when allowed, one (3,) point. C-contiguous float32 and float64 arrays
/// are read in place, anything else through a float64 copy. Reading rows needs no GIL.
class Rows3 {
 public:
  /// `allow_single`: a (3,) array is taken as one row, and results drop the leading axis.
  Rows3(py::handle object, const char* name, bool allow_single);

  [[nodiscard]] std::size_t size() const { return count_; }
  [[nodiscard]] bool single() const { return single_; }
  [[nodiscard]] Eigen::Vector3d row(std::size_t i) const;
  /// Raises ValueError naming the argument and the row when a coordinate is NaN or infinite.
  void require_finite() const;
  /// The rows as a scan: a view of float32 data, or a float32 copy of float64 data.
  [[nodiscard]] ScanView scan(std::vector<float>& storage) const;

 private:
  py::array array_;
  const char* name_;
  std::size_t count_ = 0;
  bool single_ = false;
  bool float32_ = false;
};

/// One value per point, for a scan's per-point attributes: None (an empty array) or a 1-D
/// array-like of `count` values converted to T (float32 intensities, float64 times: any real
/// dtype; uint32 ids: integer dtypes only, each value in [0, 2^32)). TypeError for the wrong
/// kind or dtype, ValueError for the wrong length or an id out of range, naming `name`.
template <class T>
[[nodiscard]] py::array_t<T> column_arg(py::handle object, const char* name, std::size_t count);

/// A finite 3-vector: a (3,) array or a sequence of three numbers.
[[nodiscard]] Eigen::Vector3d vector3_arg(py::handle object, const char* name);
/// A rigid transform: a (4, 4) array whose last row is [0, 0, 0, 1], or a (3, 4) one (KITTI's).
/// Finiteness and orthonormality are checked by the C++ update, which names the value.
[[nodiscard]] Eigen::Isometry3d pose_arg(py::handle object, const char* name);
/// A finite number (a bool is refused).
[[nodiscard]] double number_arg(py::handle object, const char* name);

/// (N, 3) array (float64 for Vector3d, float32 for Vector3f) that owns `rows` without copying.
template <class Vector>
[[nodiscard]] py::array_t<typename Vector::Scalar> rows_array(std::vector<Vector>&& rows) {
  using Scalar = typename Vector::Scalar;
  static_assert(sizeof(Vector) == 3 * sizeof(Scalar), "rows must be packed");
  auto* owned = new std::vector<Vector>(std::move(rows));
  const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<Vector>*>(p); });
  const std::size_t n = owned->size();
  return py::array_t<Scalar>({n, std::size_t(3)}, {3 * sizeof(Scalar), sizeof(Scalar)},
                             n ? owned->front().data() : nullptr, owner);
}
/// An array of the given shape (C order) that owns `values` without copying.
template <class T>
[[nodiscard]] py::array_t<T> shaped_array(std::vector<T>&& values, const std::vector<std::size_t>& shape) {
  auto* owned = new std::vector<T>(std::move(values));
  const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->empty() ? nullptr : owned->data(), owner);
}
/// (N,) array that owns `values` without copying.
template <class T>
[[nodiscard]] py::array_t<T> values_array(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  const py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({owned->size()}, {sizeof(T)}, owned->empty() ? nullptr : owned->data(),
                        owner);
}
/// (4, 4) float64 array of a transform.
[[nodiscard]] py::array_t<double> matrix_array(const Eigen::Isometry3d& pose);
/// (3,) float64 array.
[[nodiscard]] py::array_t<double> vector_array(const Eigen::Vector3d& v);

}  // namespace eco::python
