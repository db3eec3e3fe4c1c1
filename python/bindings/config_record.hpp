#pragma once
// Config and its parts (DensityCap, KeptAttributes, FreeSpaceClearing, SensorModel, Region) as records (records.hpp), for every binding that takes a Config.

#include "records.hpp"

#include <eco/config.hpp>

namespace eco::python {

template <>
struct Record<DensityCap> {
  static constexpr const char* name = "DensityCap";
  static std::vector<Field<DensityCap>> fields();  // config.cpp
};

template <>
struct Record<FreeSpaceClearing> {
  static constexpr const char* name = "FreeSpaceClearing";
  static std::vector<Field<FreeSpaceClearing>> fields();  // config.cpp
};

template <>
struct Record<KeptAttributes> {
  static constexpr const char* name = "KeptAttributes";
  static std::vector<Field<KeptAttributes>> fields();  // config.cpp
};

template <>
struct Record<SensorModel> {
  static constexpr const char* name = "SensorModel";
  static std::vector<Field<SensorModel>> fields();  // config.cpp
};

template <>
struct Record<Region> {
  static constexpr const char* name = "Region";
  static std::vector<Field<Region>> fields();  // config.cpp
};

template <>
struct Record<Config> {
  static constexpr const char* name = "Config";
  static std::vector<Field<Config>> fields();  // config.cpp
};

}  // namespace eco::python
