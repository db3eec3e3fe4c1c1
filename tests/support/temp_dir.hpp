#pragma once
// A fresh folder under the system's temp folder, removed with everything in it at scope exit.

#include <filesystem>
#include <random>
#include <string>

namespace eco::test {

class TempDir {
 public:
  explicit TempDir(const std::string& tag = "eco") {
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() /
            (tag + "-" + std::to_string(entropy()) + "-" + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace eco::test
