#pragma once
/// @file frame_window.hpp
/// The frames of a workload from the `first` on, numbered from 0 (`--start`): any source, the
/// simulator's drive included, begins where the user asks.

#include <eco/workloads/workload.hpp>

#include <memory>

namespace eco::workloads {

/// Frames [first, size) of `frames`. Throws std::invalid_argument when `first` is past its last.
[[nodiscard]] std::unique_ptr<Workload> frame_window(std::unique_ptr<Workload> frames, std::size_t first);

}  // namespace eco::workloads
