#include "sequence_gaps.hpp"

namespace gridslam::live {
namespace {

// Gaps longer than this are counted without remembering each number.
constexpr std::uint32_t kLongGap = 100'000;

}  // namespace

long SequenceGaps::Add(std::uint32_t seq) {
  if (!newest_ || static_cast<std::uint64_t>(seq) + window_ < *newest_) {
    // The first message, or a new publisher (its numbers start again).
    lost_ += static_cast<long>(missing_.size());
    missing_.clear();
    newest_ = seq;
    return lost_;
  }
  if (seq > *newest_) {
    const std::uint32_t gap = seq - *newest_ - 1;
    if (gap > kLongGap) {
      lost_ += static_cast<long>(gap);
    } else {
      for (std::uint32_t s = *newest_ + 1; s < seq; ++s) {
        missing_.insert(s);
      }
    }
    newest_ = seq;
  } else {
    missing_.erase(seq);  // a late arrival (or a repeat)
  }
  while (!missing_.empty() && static_cast<std::uint64_t>(*missing_.begin()) + window_ < *newest_) {
    missing_.erase(missing_.begin());
    ++lost_;
  }
  return lost_;
}

}  // namespace gridslam::live
