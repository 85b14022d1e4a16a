#pragma once
// How the GUI process's heap treats large blocks (glibc only; elsewhere nothing changes).
//
// A plot canvas keeps its picture in a pixmap of the canvas's size (1366 x 700: 3.7 MB) and
// makes a new one on every replot. glibc serves blocks that large with a fresh mmap and unmaps
// them on free, so every first paint touched ~700-900 new pages; on a virtual machine a page
// fault costs 20-30 us, ~10-20 ms per paint (docs/benchmarks.md, "Sixth look"). Keeping
// blocks under 16 MiB in the heap, and up to 64 MiB of freed heap in the process, lets the next
// pixmap reuse the pages of the last.

namespace driftlab {

class HeapPolicy {
public:
    // Call once, first thing in main(), before any thread starts. Returns false where the
    // C library has no such setting (the process then runs with the library's defaults).
    static bool keepLargeBlocksInHeap();

    static constexpr int kMmapThresholdBytes = 16 << 20;
    static constexpr int kTrimThresholdBytes = 64 << 20;
};

} // namespace driftlab
