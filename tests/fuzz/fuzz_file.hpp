#pragma once
// A scratch file for a fuzzer that reads through a path: one per process, removed when it exits.

#include <unistd.h>

#include <cstdio>
#include <string>

/// A file of this process's own, ending in `extension`, removed when the process exits.
class FuzzFile {
 public:
  explicit FuzzFile(const char* extension) : path_("/tmp/eco-fuzz-" + std::to_string(getpid()) + extension) {}
  FuzzFile(const FuzzFile&) = delete;
  FuzzFile& operator=(const FuzzFile&) = delete;
  ~FuzzFile() { std::remove(path_.c_str()); }
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};
