#pragma once
/// The liftmap executable's malloc settings (never the library's: a library must not change its host's allocator).

namespace liftmap_app {

/// Lets glibc's malloc keep the memory a map frees for the map's next allocations instead of giving it back to the
/// system: allocations of up to 1 GiB come from the heap (M_MMAP_THRESHOLD) and the heap is trimmed only once 1 GiB
/// of it is free at its top (M_TRIM_THRESHOLD). With glibc's defaults a buffer of more than a few MiB that a Newton
/// step frees and the next one allocates again is returned to the system and faulted back in page by page; a map
/// spent about a tenth of its time in those page faults (docs/performance.md). Does nothing when the user has set
/// GLIBC_TUNABLES (their choice) or the C library is not glibc.
void keep_freed_memory();

}  // namespace liftmap_app
