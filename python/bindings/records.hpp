#pragma once
// Plain C++ structs (Config, SimConfig, Stats, ...) as Python classes, from one table of fields
// per struct: keyword construction, checked attributes, to_dict(), ==, repr and pickling.
//
// A struct S is made a record by specialising Record<S> with `name` and `fields()`:
//
//   template <> struct Record<DensityCap> {
//     static constexpr const char* name = "DensityCap";
//     static std::vector<Field<DensityCap>> fields() {
//       return {field("cell_size", &DensityCap::cell_size, "[m] side of the density cell"), ...};
//     }
//   };
//
// Values are converted with the field's C++ type in mind: a float field takes any real number but
// not a bool or a string; an unsigned field refuses negatives; an enum field takes the enum or its
// name (any case); a nested record takes an instance, a dict of its fields, or None (defaults).
// Errors are TypeError/ValueError naming the field ("density_cap.max_points").

#include "arrays.hpp"

#include <pybind11/pybind11.h>

#include <cctype>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace eco::python {

template <class S>
struct Record;  // specialised per struct: name, fields()

template <class T, class = void>
struct is_record : std::false_type {};
template <class T>
struct is_record<T, std::void_t<decltype(Record<T>::name)>> : std::true_type {};

template <class S>
struct Field {
  std::string name;
  std::string doc;
  std::function<py::object(py::object self)> get;                      // live value
  std::function<void(S&, py::handle, const std::string& prefix)> set;  // checked
  std::function<py::object(const S&)> plain;  // ints, floats, strings, dicts: for to_dict
  std::function<std::string(const S&)> repr;
};

/// Strings given to pybind11 as docstrings must outlive the module.
inline const char* keep(std::string text) {
  static std::deque<std::string> kept;
  return kept.emplace_back(std::move(text)).c_str();
}

// --- conversions -------------------------------------------------------------------------------

template <class T>
T integer_arg(py::handle value, const std::string& name) {
  if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) {
    throw py::type_error(name + " must be an integer, got " +
                         std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  }
  const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  const auto out_of_range = [&] {
    return py::value_error(name + " = " + std::string(py::str(py::handle(i))) + " is out of range" +
                           (std::is_unsigned_v<T> ? " (must be >= 0)" : ""));
  };
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow > 0 && std::is_unsigned_v<T> && sizeof(T) == 8) {  // e.g. a 64-bit seed past 2^63
    const unsigned long long u = PyLong_AsUnsignedLongLong(i.ptr());
    if (PyErr_Occurred()) {
      PyErr_Clear();
      throw out_of_range();
    }
    return T(u);
  }
  if (overflow != 0 || v < (long long)std::numeric_limits<T>::min() ||
      (std::is_unsigned_v<T> && v < 0) ||
      (v > 0 && (unsigned long long)v > (unsigned long long)std::numeric_limits<T>::max())) {
    throw out_of_range();
  }
  return T(v);
}

/// An enum value from the enum itself or its name, in any case.
template <class E>
E enum_arg(py::handle value, const std::string& name) {
  const py::handle type = py::type::of<E>();
  if (py::isinstance(value, type)) return py::cast<E>(value);
  const py::dict members = type.attr("__members__");
  if (py::isinstance<py::str>(value)) {
    std::string wanted = py::cast<std::string>(value);
    for (char& c : wanted) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const auto& item : members) {
      std::string candidate = py::cast<std::string>(item.first);
      for (char& c : candidate) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (candidate == wanted) return py::cast<E>(item.second);
    }
  }
  std::string choices;
  for (const auto& item : members)
    choices += (choices.empty() ? "" : ", ") + py::cast<std::string>(item.first);
  const std::string got = py::repr(value);
  if (py::isinstance<py::str>(value)) {
    throw py::value_error(name + " = " + got + " is not one of: " + choices);
  }
  throw py::type_error(name + " must be a " + std::string(py::str(type.attr("__name__"))) +
                       " or its name (" + choices + "), got " + got);
}

template <class S>
S record_from_dict(const py::dict& values, const std::string& prefix);

template <class T>
T from_python(py::handle value, const std::string& name) {
  if constexpr (is_record<T>::value) {
    if (value.is_none()) return T{};
    if (py::isinstance<py::dict>(value)) {
      return record_from_dict<T>(py::reinterpret_borrow<py::dict>(value), name + ".");
    }
    if (py::isinstance(value, py::type::of<T>())) return py::cast<T>(value);
    throw py::type_error(name + " must be a " + std::string(Record<T>::name) +
                         ", a dict of its fields or None, got " + std::string(py::repr(value)));
  } else if constexpr (std::is_enum_v<T>) {
    return enum_arg<T>(value, name);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!py::isinstance<py::bool_>(value)) throw py::type_error(name + " must be a bool");
    return py::cast<bool>(value);
  } else if constexpr (std::is_floating_point_v<T>) {
    return T(number_arg(value, name.c_str()));
  } else {
    return integer_arg<T>(value, name);
  }
}

template <class S>
py::dict record_to_dict(const S& s);

template <class T>
py::object to_plain(const T& value) {
  if constexpr (is_record<T>::value) {
    return record_to_dict(value);
  } else if constexpr (std::is_enum_v<T>) {
    return py::cast(value).attr("name");
  } else {
    return py::cast(value);
  }
}

template <class S>
std::string record_repr(const S& s);

template <class T>
std::string repr_of(const T& value) {
  if constexpr (is_record<T>::value) {
    return record_repr(value);
  } else if constexpr (std::is_enum_v<T>) {
    return py::str(py::cast(value));  // Recentring.Quantised
  } else {
    return py::repr(py::cast(value));
  }
}

/// The field `name` of S, held in `member`.
template <class S, class T>
Field<S> field(const char* name, T S::*member, const std::string& doc) {
  Field<S> f;
  f.name = name;
  f.doc = doc;
  f.get = [member](py::object self) -> py::object {
    S& s = py::cast<S&>(self);
    if constexpr (is_record<T>::value) {  // a view, so cfg.density_cap.max_points = 2 sticks
      return py::cast(&(s.*member), py::return_value_policy::reference_internal, self);
    } else {
      return py::cast(s.*member);
    }
  };
  f.set = [member, name](S& s, py::handle value, const std::string& prefix) {
    s.*member = from_python<T>(value, prefix + name);
  };
  f.plain = [member](const S& s) { return to_plain(s.*member); };
  f.repr = [member](const S& s) { return repr_of(s.*member); };
  return f;
}

// --- whole records -----------------------------------------------------------------------------

template <class S>
const std::vector<Field<S>>& fields_of() {
  static const std::vector<Field<S>> fields = Record<S>::fields();
  return fields;
}

template <class S>
void validate_record(const S& s) {
  if constexpr (requires { s.validate(); }) s.validate();
}

template <class S>
S record_from_dict(const py::dict& values, const std::string& prefix) {
  S s{};
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    bool found = false;
    for (const Field<S>& f : fields_of<S>()) {
      if (f.name == name) {
        f.set(s, value, prefix);
        found = true;
        break;
      }
    }
    if (!found) {
      std::string known;
      for (const Field<S>& f : fields_of<S>()) known += (known.empty() ? "" : ", ") + f.name;
      throw py::type_error(std::string(Record<S>::name) +
                           "() got an unexpected keyword argument '" + prefix + name +
                           "' (fields: " + known + ")");
    }
  }
  validate_record(s);
  return s;
}

/// What a constructor like EgoOctree(config=None, **fields) was given: a record (or a dict of
/// its fields), or its fields as keyword arguments, never both.
template <class S>
S config_or_fields(const py::object& config, const py::kwargs& fields, const char* owner) {
  if (config.is_none()) return record_from_dict<S>(fields, "");
  if (!fields.empty()) {
    throw py::type_error(std::string(owner) + "() takes either config or keyword fields, not both");
  }
  return from_python<S>(config, "config");
}

template <class S>
py::dict record_to_dict(const S& s) {
  py::dict out;
  for (const Field<S>& f : fields_of<S>()) out[py::str(f.name)] = f.plain(s);
  return out;
}

template <class S>
std::string record_repr(const S& s) {
  std::string out = std::string(Record<S>::name) + "(";
  bool first = true;
  for (const Field<S>& f : fields_of<S>()) {
    out += (first ? "" : ", ") + f.name + "=" + f.repr(s);
    first = false;
  }
  return out + ")";
}

/// The docstring of a record: its purpose, then one line per field with its default.
template <class S>
std::string record_doc(const std::string& summary) {
  std::string out = summary + "\n\nFields (keyword arguments), with their defaults:\n";
  const S defaults{};
  for (const Field<S>& f : fields_of<S>()) {
    out += "    " + f.name + " = " + f.repr(defaults) + "\n        " + f.doc + "\n";
  }
  return out;
}

enum class Access { ReadWrite, ReadOnly };

/// Binds S as a Python class. ReadWrite: constructed from keyword arguments (checked, then
/// validated when S has validate()), attributes assignable (checked), picklable. ReadOnly: results
/// the library returns.
template <class S>
py::class_<S> bind_record(py::handle scope, const std::string& summary, Access access) {
  py::class_<S> cls(scope, Record<S>::name, keep(record_doc<S>(summary)));
  if (access == Access::ReadWrite) {
    cls.def(py::init([](const py::kwargs& values) { return record_from_dict<S>(values, ""); }),
            keep(std::string("Builds a ") + Record<S>::name +
                 " from keyword arguments named as its fields; the rest keep their defaults. "
                 "Raises TypeError for an unknown field or a value of the wrong type, ValueError "
                 "for a value out of range."));
    cls.def(py::pickle([](const S& s) { return record_to_dict(s); },
                       [](const py::dict& d) { return record_from_dict<S>(d, ""); }));
    if constexpr (requires(const S& s) { s.validate(); }) {
      cls.def("validate", &S::validate,
              "Raises ValueError naming the first field whose value is unusable.");
    }
  }
  for (const Field<S>& f : fields_of<S>()) {
    const py::cpp_function getter([get = f.get](py::object self) { return get(self); });
    if (access == Access::ReadWrite) {
      const py::cpp_function setter([set = f.set](S& s, py::handle value) { set(s, value, ""); },
                                    py::is_method(cls));
      cls.def_property(f.name.c_str(), getter, setter, keep(f.doc));
    } else {
      cls.def_property_readonly(f.name.c_str(), getter, keep(f.doc));
    }
  }
  cls.def(
      "to_dict", [](const S& s) { return record_to_dict(s); },
      "The fields as a dict of plain Python values (enums by name, nested records as dicts), "
      "ready for json.dumps; the class's constructor takes it back as keyword arguments.");
  cls.def("__repr__", [](const S& s) { return record_repr(s); });
  cls.def("__eq__", [](const S& a, py::object b) {
    return py::isinstance<S>(b) && record_to_dict(a).equal(record_to_dict(py::cast<const S&>(b)));
  });
  cls.attr("__hash__") = py::none();
  return cls;
}

}  // namespace eco::python
