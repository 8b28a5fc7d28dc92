#include "gridslam/io/timestamp_repair.hpp"

#include <algorithm>
#include <limits>

#include "gridslam/common/check.hpp"

namespace gridslam::io {
namespace {

// Forward gaps cost their square (evenly spaced times are cheapest, and unlike a linear cost the
// sum does not telescope to last - first); a step backwards costs far more.
constexpr double kBackwardWeight = 10.0;   // per second of going backwards
constexpr double kInversionPenalty = 1.0;  // fixed cost of any backward step
constexpr double kUnpadPrior = 2e-2;       // cost of reading a time as unpadded [s^2]
constexpr double kTieBreak = 1e-9;         // prefer fewer dropped zeros among equals

double Transition(Time from, Time to) {
  const double d = ToSeconds(to - from);
  return d >= 0.0 ? d * d : kBackwardWeight * (-d) + kInversionPenalty;
}

double Prior(std::size_t candidate) {
  return candidate == 0 ? 0.0 : kUnpadPrior + kTieBreak * static_cast<double>(candidate);
}

}  // namespace

std::vector<Time> UnpaddedCandidates(std::string_view text, Time printed) {
  std::vector<Time> out{printed};
  const auto dot = text.find('.');
  if (dot == std::string_view::npos || text.size() - dot - 1 != 6 || text.front() == '-') {
    return out;
  }
  const std::string_view fraction = text.substr(dot + 1);
  std::int64_t micros = 0;
  for (char c : fraction) {
    if (c < '0' || c > '9') {
      return out;
    }
    micros = micros * 10 + (c - '0');
  }
  if (micros == 0) {
    return out;
  }
  const Time whole = printed - Duration(micros * 1000);
  while (micros % 10 == 0) {
    micros /= 10;
    out.push_back(whole + Duration(micros * 1000));
  }
  return out;
}

bool HasSmallFraction(std::string_view text) {
  const auto dot = text.find('.');
  return dot == std::string_view::npos || dot + 1 >= text.size() || text[dot + 1] == '0';
}

TimestampRepairer::TimestampRepairer(std::size_t lag, std::size_t detect_count,
                                     std::size_t min_count)
    : lag_(std::max<std::size_t>(lag, 1)),
      detect_count_(std::max<std::size_t>(detect_count, 1)),
      min_count_(min_count) {}

void TimestampRepairer::Push(std::uint64_t id, std::string_view text, Time printed) {
  switch (mode_) {
    case Mode::kIdentity:
      ready_.emplace_back(id, printed);
      return;
    case Mode::kRepair:
      AddStep(id, UnpaddedCandidates(text, printed));
      return;
    case Mode::kUndecided:
      undecided_.emplace_back(id, UnpaddedCandidates(text, printed));
      if (HasSmallFraction(text)) {
        Decide(Mode::kIdentity);
      } else if (undecided_.size() >= detect_count_) {
        Decide(Mode::kRepair);
      }
      return;
  }
}

void TimestampRepairer::Decide(Mode mode) {
  mode_ = mode;
  for (auto& [id, candidates] : undecided_) {
    if (mode == Mode::kIdentity) {
      ready_.emplace_back(id, candidates.front());
    } else {
      AddStep(id, std::move(candidates));
    }
  }
  undecided_.clear();
}

void TimestampRepairer::AddStep(std::uint64_t id, std::vector<Time> candidates) {
  GRIDSLAM_CHECK(!candidates.empty()) << "no timestamp candidates";
  Step step{id, std::move(candidates), {}};
  std::vector<double> cost(step.candidates.size(), 0.0);
  step.back.assign(step.candidates.size(), -1);
  for (std::size_t b = 0; b < step.candidates.size(); ++b) {
    const double prior = Prior(b);
    if (pending_.empty()) {
      // Start of the stream or right after a commit: anchor on the last committed time.
      cost[b] = prior + (last_committed_ ? Transition(*last_committed_, step.candidates[b]) : 0.0);
      continue;
    }
    const Step& prev = pending_.back();
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < prev.candidates.size(); ++a) {
      const double c = cost_[a] + Transition(prev.candidates[a], step.candidates[b]);
      if (c < best) {
        best = c;
        step.back[b] = static_cast<int>(a);
      }
    }
    cost[b] = best + prior;
  }
  cost_ = std::move(cost);
  pending_.push_back(std::move(step));
  while (pending_.size() > lag_) {
    CommitOldest();
  }
}

void TimestampRepairer::CommitOldest() {
  // Backtrack from the best candidate of the newest step to the oldest pending step. The newest
  // entries have no successors yet to constrain them, so the newest is anchored to its printed
  // value (squared distance): otherwise the tail of the window would be squeezed into ever
  // smaller gaps.
  const Step& newest = pending_.back();
  int k = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < cost_.size(); ++b) {
    const double d = ToSeconds(newest.candidates[0] - newest.candidates[b]);
    if (cost_[b] + d * d < best) {
      best = cost_[b] + d * d;
      k = static_cast<int>(b);
    }
  }
  for (std::size_t s = pending_.size() - 1; s > 0; --s) {
    k = pending_[s].back[static_cast<std::size_t>(k)];
  }
  const Time chosen = pending_.front().candidates[static_cast<std::size_t>(k)];
  ready_.emplace_back(pending_.front().id, chosen);
  last_committed_ = chosen;
  pending_.pop_front();
  if (!pending_.empty()) {
    // Paths through other choices of the committed step are no longer possible.
    pending_.front().back.assign(pending_.front().candidates.size(), -1);
  }
}

void TimestampRepairer::Flush() {
  if (mode_ == Mode::kUndecided) {
    Decide(undecided_.size() >= min_count_ ? Mode::kRepair : Mode::kIdentity);
  }
  while (!pending_.empty()) {
    CommitOldest();
  }
}

std::optional<std::pair<std::uint64_t, Time>> TimestampRepairer::Pop() {
  if (ready_.empty()) {
    return std::nullopt;
  }
  auto front = ready_.front();
  ready_.pop_front();
  return front;
}

}  // namespace gridslam::io
