// Scratch buffers kept per thread from call to call (docs/speed.md, "Round 17"): a key map's
// buffers are a few MB, and allocated afresh on every call they cost the kernel's page faults
// again. A thread that is done with the heavy work hands its buffers back with
// ReleaseThreadScratch(), so they do not sit in its memory through a later stage (the caller
// thread of `gridslam map` before the outputs).
#pragma once

#include <utility>

namespace gridslam {

namespace internal {
/// Adds `reset` to the calling thread's list of scratch resets.
void RegisterThreadScratch(void (*reset)());
}  // namespace internal

/// The calling thread's scratch object of type T for the tag `Tag` (a type private to the user,
/// so that two users never share one), value-initialized on the thread's first use or after a
/// release. Whoever reads it must write it first: its contents are those the thread left.
template <typename Tag, typename T>
T& ThreadScratch() {
  thread_local T value{};
  thread_local bool registered = false;
  if (!registered) {
    registered = true;
    internal::RegisterThreadScratch([] {
      T fresh{};
      std::swap(ThreadScratch<Tag, T>(), fresh);  // the old buffers die with `fresh`
    });
  }
  return value;
}

/// Frees the memory of every ThreadScratch object of the calling thread (each becomes a
/// value-initialized T); other threads' are untouched.
void ReleaseThreadScratch();

}  // namespace gridslam
