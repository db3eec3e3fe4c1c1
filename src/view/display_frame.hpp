#pragma once
// A frame as the page draws it: what the server sends for /api/frame. Held points beyond the
// page's budget are thinned on the server by keeping every k-th in the recorded order (the tree's
// order, leaf by leaf, so the kept points cover the map evenly), k = ceil(held / budget); the
// dropped and cleared points by the same k, so that they keep the held points' density; the voxel
// map by its own k, ceil(voxels / budget).

#include "view/frame_file.hpp"

#include <string>

namespace eco::view {

/// Little-endian: a uint32 n, n bytes of JSON (the frame's counts, the strides used and `step`,
/// padded with spaces to a multiple of 4), then per drawn held point its position minus the
/// sensor's as int16 × 3 in units of `step` and its age as uint16, then (when the frame has them)
/// float32 intensities and uint32 ids, then float32 xyz minus the sensor position of the drawn
/// dropped points, cleared points and voxel centres.
/// Without `with_voxels` no voxel centre is sent (voxels_drawn is 0; voxels still counts them).
[[nodiscard]] std::string display_bytes(const FrameRecord& record, std::size_t budget, bool with_voxels = true);

/// k of "every k-th": the stride that keeps at most `budget` of `count` (1 when all fit).
[[nodiscard]] std::size_t thinning_stride(std::size_t count, std::size_t budget);

}  // namespace eco::view
