#include "bench/map_file_timing.hpp"

#include "bench/stopwatch.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace eco::bench {
namespace {

/// The raw floor: one write of `bytes`, flushed to the disk, and one read back.
void write_and_read_raw(const std::string& path, const std::string& bytes, std::string& back) {
  const int out = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0) throw std::runtime_error(path + ": cannot create");
  const bool written = ::write(out, bytes.data(), bytes.size()) == ssize_t(bytes.size()) && ::fsync(out) == 0;
  ::close(out);
  if (!written) throw std::runtime_error(path + ": cannot write");
  const int in = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw std::runtime_error(path + ": cannot open");
  back.resize(bytes.size());
  const bool read = ::read(in, back.data(), back.size()) == ssize_t(back.size());
  ::close(in);
  if (!read) throw std::runtime_error(path + ": cannot read");
}

}  // namespace

MapFileTiming time_map_file(const EgoOctree& tree, int rounds) {
  std::random_device entropy;
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(entropy());
  const std::string path = (folder / ("eco-bench-" + tag + ".eco")).string();
  const std::string raw_path = (folder / ("eco-bench-" + tag + ".raw")).string();
  MapFileTiming t;
  t.save_ms = t.load_ms = t.raw_ms = std::numeric_limits<double>::infinity();
  std::size_t loaded = 0;
  for (int r = 0; r < rounds; ++r) {
    auto start = Clock::now();
    tree.save(path);
    t.save_ms = std::min(t.save_ms, ms_since(start));
    start = Clock::now();
    loaded += EgoOctree::load(path).size();
    t.load_ms = std::min(t.load_ms, ms_since(start));
  }
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  std::string back;
  for (int r = 0; r < rounds; ++r) {
    const auto start = Clock::now();
    write_and_read_raw(raw_path, bytes, back);
    t.raw_ms = std::min(t.raw_ms, ms_since(start));
  }
  std::filesystem::remove(path);
  std::filesystem::remove(raw_path);
  if (loaded != tree.size() * std::size_t(rounds) || back != bytes) throw std::runtime_error("map file: read back wrong");
  t.file_bytes = bytes.size();
  const KeptAttributes& a = tree.config().attributes;
  const std::size_t columns = std::size_t(a.ids) + std::size_t(a.intensity) + std::size_t(a.time);
  t.point_bytes = tree.size() * (12 + 4 * columns);
  return t;
}

}  // namespace eco::bench
