#include "arrays.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <sstream>
#include <string>

namespace eco::python {

using namespace pybind11::literals;

namespace {

std::string type_name(py::handle object) {
  return py::str(py::type::handle_of(object).attr("__name__"));
}

std::string shape_of(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

std::string describe(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return s.str();
}

/// Lists, tuples and objects numpy can read (__array__) become arrays; anything else is refused.
py::array as_array(py::handle object, const char* name) {
  if (py::isinstance<py::array>(object)) return py::reinterpret_borrow<py::array>(object);
  const bool listlike = py::isinstance<py::list>(object) || py::isinstance<py::tuple>(object);
  if (!listlike && !py::hasattr(object, "__array__")) {
    throw py::type_error(std::string(name) + " must be a numpy array (or a list of numbers), got " +
                         type_name(object));
  }
  try {
    return py::module_::import("numpy").attr("asarray")(object, "dtype"_a = listlike ? py::object(py::str("float64"))
                                                                                      : py::object(py::none()));
  } catch (const py::error_already_set& e) {
    throw py::type_error(std::string(name) + " is not a list of numbers: " + e.what());
  }
}

/// Refuses arrays that do not hold real numbers (bool, complex, strings, objects, dates).
void require_real(const py::array& a, const char* name) {
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::type_error(std::string(name) + " must hold real numbers, got dtype " +
                         std::string(py::str(py::handle(a.dtype()))));
  }
}

/// A small argument (a vector, a pose) of any real dtype and layout, as float64.
py::array_t<double> small_array(py::handle object, const char* name) {
  const py::array a = as_array(object, name);
  require_real(a, name);
  return py::array_t<double, py::array::c_style | py::array::forcecast>(a);
}

}  // namespace

Rows3::Rows3(py::handle object, const char* name, bool allow_single)
    : array_(as_array(object, name)), name_(name) {
  require_real(array_, name);
  single_ = allow_single && array_.ndim() == 1 && array_.shape(0) == 3;
  if (!single_ && !(array_.ndim() == 2 && array_.shape(1) == 3)) {
    throw py::value_error(std::string(name) + " must have shape (N, 3)" +
                          (allow_single ? " or (3,)" : "") + ", got " + shape_of(array_));
  }
  // C-contiguous float32 and float64 are read in place; anything else is copied to float64.
  const bool in_place = (array_.flags() & py::array::c_style) != 0;
  float32_ = in_place && array_.dtype().equal(py::dtype::of<float>());
  if (!float32_ && !(in_place && array_.dtype().equal(py::dtype::of<double>()))) {
    array_ = py::array_t<double, py::array::c_style | py::array::forcecast>(array_);
  }
  count_ = single_ ? 1 : std::size_t(array_.shape(0));
}

Eigen::Vector3d Rows3::row(std::size_t i) const {
  if (float32_) {
    const float* p = static_cast<const float*>(array_.data()) + 3 * i;
    return {p[0], p[1], p[2]};
  }
  const double* p = static_cast<const double*>(array_.data()) + 3 * i;
  return {p[0], p[1], p[2]};
}

void Rows3::require_finite() const {
  for (std::size_t i = 0; i < count_; ++i) {
    const Eigen::Vector3d v = row(i);
    if (!v.allFinite()) {
      throw py::value_error(std::string(name_) + (single_ ? "" : " row " + std::to_string(i)) +
                            " is not finite: " + describe(v));
    }
  }
}

ScanView Rows3::scan(std::vector<float>& storage) const {
  if (float32_) return {static_cast<const float*>(array_.data()), count_, 3};
  const double* p = static_cast<const double*>(array_.data());
  storage.assign(p, p + 3 * count_);
  return {storage.data(), count_, 3};
}

template <class T>
py::array_t<T> column_arg(py::handle object, const char* name, std::size_t count) {
  if (object.is_none()) return py::array_t<T>(0);
  const bool listlike = py::isinstance<py::list>(object) || py::isinstance<py::tuple>(object);
  const py::array a = listlike ? py::array(py::module_::import("numpy").attr("asarray")(object)) : as_array(object, name);
  require_real(a, name);
  if constexpr (std::is_integral_v<T>) {
    const char kind = a.dtype().kind();
    if (kind != 'i' && kind != 'u') {
      throw py::type_error(std::string(name) + " must hold integers, got dtype " +
                           std::string(py::str(py::handle(a.dtype()))));
    }
  }
  if (a.ndim() != 1 || std::size_t(a.shape(0)) != count) {
    throw py::value_error(std::string(name) + " must have one value per point, shape (" + std::to_string(count) +
                          ",), got " + shape_of(a));
  }
  if constexpr (std::is_integral_v<T>) {
    if (count > 0) {
      const py::int_ least(a.attr("min")()), most(a.attr("max")());
      if (least < py::int_(0) || most > py::int_(std::numeric_limits<T>::max())) {
        throw py::value_error(std::string(name) + " must lie in [0, " + std::to_string(std::numeric_limits<T>::max()) +
                              "], got values from " + std::string(py::str(py::handle(least))) + " to " + std::string(py::str(py::handle(most))));
      }
    }
  }
  return py::array_t<T, py::array::c_style | py::array::forcecast>(a);
}

template py::array_t<std::uint32_t> column_arg<std::uint32_t>(py::handle, const char*, std::size_t);
template py::array_t<float> column_arg<float>(py::handle, const char*, std::size_t);
template py::array_t<double> column_arg<double>(py::handle, const char*, std::size_t);

Eigen::Vector3d vector3_arg(py::handle object, const char* name) {
  const py::array_t<double> a = small_array(object, name);
  if (a.ndim() != 1 || a.shape(0) != 3) {
    throw py::value_error(std::string(name) + " must have 3 coordinates, got shape " + shape_of(a));
  }
  const auto v = a.unchecked<1>();
  const Eigen::Vector3d out(v(0), v(1), v(2));
  if (!out.allFinite()) {
    throw py::value_error(std::string(name) + " is not finite: " + describe(out));
  }
  return out;
}

Eigen::Isometry3d pose_arg(py::handle object, const char* name) {
  const py::array_t<double> a = small_array(object, name);
  if (a.ndim() != 2 || a.shape(1) != 4 || (a.shape(0) != 4 && a.shape(0) != 3)) {
    throw py::value_error(std::string(name) + " must be a 4x4 (or 3x4) transform, got shape " +
                          shape_of(a));
  }
  const auto m = a.unchecked<2>();
  if (a.shape(0) == 4 && !(m(3, 0) == 0.0 && m(3, 1) == 0.0 && m(3, 2) == 0.0 && m(3, 3) == 1.0)) {
    std::ostringstream s;
    s << name << " must have last row [0, 0, 0, 1], got [" << m(3, 0) << ", " << m(3, 1) << ", "
      << m(3, 2) << ", " << m(3, 3) << "]";
    throw py::value_error(s.str());
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = m(r, c);
  }
  return pose;
}

double number_arg(py::handle object, const char* name) {
  if (py::isinstance<py::bool_>(object) || !PyNumber_Check(object.ptr()) ||
      py::isinstance<py::str>(object)) {
    throw py::type_error(std::string(name) + " must be a number, got " + type_name(object));
  }
  return py::cast<double>(py::float_(py::reinterpret_borrow<py::object>(object)));
}

py::array_t<double> matrix_array(const Eigen::Isometry3d& pose) {
  py::array_t<double> out({4, 4});
  auto m = out.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = pose.matrix()(r, c);
  }
  return out;
}

py::array_t<double> vector_array(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  auto a = out.mutable_unchecked<1>();
  for (int i = 0; i < 3; ++i) a(i) = v[i];
  return out;
}

}  // namespace eco::python
