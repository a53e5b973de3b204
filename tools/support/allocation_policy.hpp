// Process-wide allocator policy for tools whose run is many passes over large arrays (volmap-map;
// tools only, the library never sets it). Such a run is one short process over a few large flat
// arrays that are freed and allocated again at the same sizes (untangler iterations, stage copies).
// glibc serves blocks above a dynamic threshold (128 KiB at start) with fresh mmap'd pages and
// unmaps them on free, so every such cycle pays the page faults and zeroing again (volmap-map on a
// 100k-tet pair: 23k faults, ~0.2 s of system time, 15 % of the run). Blocks up to 32 MiB (glibc's
// ceiling for the threshold) are kept in the heap instead and the heap is not trimmed: freed memory
// is reused. The peak can grow a little by fragmentation, which is why the one-pass tools (e.g.
// volmap-metrics, whose peak memory is a target) do not set it. No effect outside glibc.
#pragma once

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace volmap_tools {

inline void reuse_freed_memory() {
#if defined(__GLIBC__)
  (void)mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  (void)mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace volmap_tools
