#pragma once
// A stage reads the scan once, front to back, a group at a time; the hardware prefetcher stops at
// every 4 KB page, so each page's first loads would wait on memory. The stage asks for the scan a
// few groups ahead instead (docs/benchmarks.md, session 25: the capped update 6-17 % faster).

#include <eco/types.hpp>

#include <cstddef>

namespace eco::detail {

/// Points ahead of the group being read that a stage asks for: 4 KB at 16 B a point.
inline constexpr std::size_t kScanAhead = 256;

/// Starts loading the `count` points of `scan` from `from` on (those that exist).
inline void prefetch_scan(ScanView scan, std::size_t from, std::size_t count) {
  if (from >= scan.count) return;
  const std::size_t n = scan.count - from < count ? scan.count - from : count;
  const char* begin = reinterpret_cast<const char*>(scan.data + from * scan.stride);
  const char* end = reinterpret_cast<const char*>(scan.data + (from + n) * scan.stride);
  for (const char* at = begin; at < end; at += 64) __builtin_prefetch(at);
}

}  // namespace eco::detail
