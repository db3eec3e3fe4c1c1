#pragma once
// What the recording fuzzers share: the bytes written to a file of the container's extension, then
// read as a recording, every cloud decoded; an eco::io::Error is the one way out allowed.

#include <eco/io/error.hpp>
#include <eco/io/recording.hpp>

#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <string>

inline void read_as_recording(const std::uint8_t* data, std::size_t size, const std::string& path) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    eco::io::Recording bag(path, {});
    for (std::size_t i = 0; i < bag.size(); ++i) (void)bag.read(i);
  } catch (const eco::io::Error&) {
  }
}

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
