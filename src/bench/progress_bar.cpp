#include "bench/progress_bar.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

namespace eco::bench {

Progress terminal_progress() {
  Progress p;
  const bool tty = isatty(STDERR_FILENO) != 0;
  p.status = [](const std::string& what) { std::fprintf(stderr, "%s\n", what.c_str()); };
  auto start = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  p.frame = [tty, start](std::size_t done, std::size_t total, const BenchRun& run) {
    if (!tty) return;
    if (done == 1) *start = std::chrono::steady_clock::now();
    constexpr int kWidth = 30;
    const int filled = int(double(kWidth) * double(done) / double(total));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - *start).count();
    const double eta = done > 0 ? seconds / double(done) * double(total - done) : 0.0;
    std::string line = "\r[" + std::string(std::size_t(filled), '#') + std::string(std::size_t(kWidth - filled), ' ') +
                       "] " + std::to_string(done) + "/" + std::to_string(total) + "  eta " +
                       std::to_string(int(eta)) + " s ";
    for (const MethodRun& m : run.methods) {
      char figure[64];
      std::snprintf(figure, sizeof figure, " %s %.1f ms", m.name.c_str(), m.frames.back().update_ms);
      line += figure;
    }
    std::fprintf(stderr, "%s\033[K", line.c_str());
    if (done == total) std::fprintf(stderr, "\n");
  };
  return p;
}

}  // namespace eco::bench
