#pragma once
// Where the real KITTI and BALM frames are: $ECO_DATA_DIR, else shared/data in the folder that
// holds the checkout or the nearest folder above it that has one. Tests that need them skip,
// saying where they looked, when they are absent.

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace eco::test {

inline std::filesystem::path shared_data_dir() {
  if (const char* env = std::getenv("ECO_DATA_DIR"); env && *env) return env;
  const auto checkout = std::filesystem::absolute(ECO_SOURCE_DIR).lexically_normal();
  for (auto folder = checkout.parent_path(); !folder.empty(); folder = folder.parent_path()) {
    if (std::filesystem::is_directory(folder / "shared" / "data")) return folder / "shared" / "data";
    if (folder == folder.root_path()) break;
  }
  return checkout.parent_path() / "shared" / "data";
}

/// The named dataset's folder, or nullopt when it is absent.
inline std::optional<std::filesystem::path> shared_dataset(const std::string& name) {
  const auto folder = shared_data_dir() / name;
  if (std::filesystem::is_directory(folder / "velodyne")) return folder;
  return std::nullopt;
}

}  // namespace eco::test

/// Skips the current test, naming the folder it needs, when a dataset is absent.
#define ECO_REQUIRE_DATASET(var, name)                                                       \
  const auto var##_found = ::eco::test::shared_dataset(name);                                \
  if (!var##_found) {                                                                        \
    GTEST_SKIP() << "real data absent: " << (::eco::test::shared_data_dir() / (name)).string() \
                 << " not found (set ECO_DATA_DIR to the folder holding " << (name) << ")";   \
  }                                                                                          \
  const std::filesystem::path var = *var##_found
