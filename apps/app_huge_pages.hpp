// Transparent huge pages for the heap (issue 19; docs/speed.md, round 23). The mapper touches
// a few hundred MB of grids, fields and key maps; in 4 KiB pages that is some 76 000 page faults
// on fr079, 13 % of the front end's time. glibc 2.35 and later ask the kernel for huge pages for
// their heap when the tunable glibc.malloc.hugetlb=1 is set, but read it from the environment at
// start-up only: so the program re-executes itself once with it set (0.02 s). Measured: 4-8 %
// less wall time on the labelled logs, 1-2 % more peak memory, the same outputs.
#pragma once

namespace gridslam::app {

/// Re-executes this program (same arguments, same process) with glibc.malloc.hugetlb=1 in
/// GLIBC_TUNABLES, unless: GLIBC_TUNABLES is already set (the user's choice, and the mark of the
/// re-executed process), GRIDSLAM_HUGE_PAGES=0, the kernel gives huge pages only when asked
/// ("madvise") is not its setting, the C library is not glibc 2.35 or later, or a sanitizer or
/// valgrind runs the program. Returns when it does not re-execute, or when exec fails.
void ReexecWithHugePages(char** argv);

}  // namespace gridslam::app
