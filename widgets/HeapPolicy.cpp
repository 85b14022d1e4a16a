#include "HeapPolicy.h"

#include <cstdlib> // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace driftlab {

bool HeapPolicy::keepLargeBlocksInHeap()
{
#if defined(__GLIBC__)
    // Setting either threshold turns off glibc's sliding mmap threshold; both are set so that
    // a freed pixmap at the top of the heap is neither unmapped nor trimmed.
    return mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes) == 1 && mallopt(M_TRIM_THRESHOLD, kTrimThresholdBytes) == 1;
#else
    return false;
#endif
}

} // namespace driftlab
