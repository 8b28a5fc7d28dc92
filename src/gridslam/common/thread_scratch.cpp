#include "gridslam/common/thread_scratch.hpp"

#include <vector>

namespace gridslam {

namespace {

std::vector<void (*)()>& Resets() {
  thread_local std::vector<void (*)()> resets;
  return resets;
}

}  // namespace

namespace internal {

void RegisterThreadScratch(void (*reset)()) { Resets().push_back(reset); }

}  // namespace internal

void ReleaseThreadScratch() {
  for (void (*reset)() : Resets()) {
    reset();
  }
}

}  // namespace gridslam
