#pragma once
// Config and DensityCap as records (records.hpp), for every binding that takes a Config.

#include "records.hpp"

#include <eco/config.hpp>

namespace eco::python {

template <>
struct Record<DensityCap> {
  static constexpr const char* name = "DensityCap";
  static std::vector<Field<DensityCap>> fields();  // config.cpp
};

template <>
struct Record<Config> {
  static constexpr const char* name = "Config";
  static std::vector<Field<Config>> fields();  // config.cpp
};

}  // namespace eco::python
