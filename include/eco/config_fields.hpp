#pragma once
/// @file config_fields.hpp
/// The fields of eco::Config as one table: name, kind, unit, default, valid range and a one-line
/// doc each. Config::validate(), the `eco` command's flags, config.json and the Python records are
/// all made from it, so every surface spells a field, its values and its errors the same way.

#include <eco/config.hpp>

#include <span>
#include <string>
#include <string_view>

namespace eco {

struct ConfigField {
  enum class Kind { Real, Count, Choice, Switch };  ///< Switch: a bool, spelled false | true

  std::string_view name;  ///< as in C++; a nested field is dotted: "density_cap.cell_size"
  Kind kind;
  std::string_view unit;  ///< "m", "frames", "points" or "" (a pure number or a choice)
  std::string_view doc;   ///< one line
  double lo = 0.0;        ///< valid range [lo, hi] (Real and Count)
  double hi = 0.0;
  bool lo_open = false;   ///< (lo, hi] instead
  std::span<const std::string_view> choices;  ///< Choice: value i's spelling (C++'s enumerator, or for the region's its lower-case name)
  double (*get)(const Config&) = nullptr;     ///< the value; a Choice's index
  void (*set)(Config&, double) = nullptr;

  /// The range as text: "(0, 1e+05]", "1..5", "AllInBox | ShiftInOnly", "false | true".
  [[nodiscard]] std::string range() const;
  /// The value of this field in `config` as text: "20", "0.1", "AllInBox".
  [[nodiscard]] std::string format(const Config& config) const;
  /// The doc line with range, unit and `defaults`' value: "L: side … [(0, 1e+05] m; default 20]",
  /// as the flags' help and the Python docstrings show it.
  [[nodiscard]] std::string summary(const Config& defaults = {}) const;
  /// The default, as format() writes it.
  [[nodiscard]] std::string default_text() const { return format(Config{}); }
  /// Sets this field of `config` from text (a number; a Choice's spelling or a Switch's false/true
  /// in any case). Throws
  /// std::invalid_argument naming the field and the text when it is not one, or is out of range;
  /// `config` is unchanged then.
  void parse(Config& config, std::string_view text) const;
  /// Throws std::invalid_argument naming the field and value unless `value` is in range.
  void check(double value) const;
};

/// Every field of Config, in declaration order.
[[nodiscard]] std::span<const ConfigField> config_fields();
/// The field called `name`; throws std::invalid_argument listing the names when there is none.
[[nodiscard]] const ConfigField& config_field(std::string_view name);

}  // namespace eco
