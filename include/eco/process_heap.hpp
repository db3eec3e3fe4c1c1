#pragma once
/// @file process_heap.hpp
/// One call for a program that runs a frame loop: the C library keeps what its frames free for the
/// next frames instead of handing it back to the kernel and faulting it in again.
///
/// A LiDAR pipeline allocates a few scan-sized buffers a frame (a copy of the scan, a filtered
/// one, a downsampling grid) and frees them by the frame's end. glibc maps a block from 128 KiB up
/// afresh and unmaps it when freed, and gives the heap's free end back to the kernel past 128 KiB;
/// it raises both thresholds only when the process frees a large mapped block, as a map kept on
/// the heap does when it grows. ECO keeps its memory in mappings of its own (so that the caller's
/// heap is left as if no map were there), so beside it, as with no map at all, every frame's
/// buffers are fresh pages: ~720 page faults a frame for the preprocessing of a KITTI scan
/// (examples/caller_faults.cpp; docs/benchmarks.md, "What a map costs its caller").
///
/// The `eco` command and the Python module make this call themselves.

#include <cstddef>

namespace eco {

/// Blocks under 32 MiB come from the heap and the heap keeps up to `keep_bytes` free at its end,
/// in every arena (glibc's M_MMAP_THRESHOLD and M_TRIM_THRESHOLD; both then stay put). The
/// process holds up to that much more than it uses, in exchange for no page faults on memory it
/// freed. Returns false where the C library has no such settings (not glibc) or refused them; the
/// process then runs as before.
bool keep_freed_heap(std::size_t keep_bytes = std::size_t{128} << 20);

}  // namespace eco
