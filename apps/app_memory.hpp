// Memory housekeeping of the apps (issue 19).
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace gridslam::app {

/// Hands the heap's free pages back to the system (glibc keeps them otherwise): after a large
/// structure is freed, the peak resident memory of what follows is then what it holds, not that
/// plus what was held before.
inline void ReleaseFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace gridslam::app
