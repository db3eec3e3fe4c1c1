#pragma once
// What the recording fuzzers share: the bytes written to a file of the container's extension, then
// read as a recording, every cloud decoded; an eco::io::Error is the one way out allowed.

#include <eco/io/error.hpp>
#include <eco/io/recording.hpp>

#include "fuzz_file.hpp"

#include <cstddef>
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
