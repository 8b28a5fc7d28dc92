#include "gridslam/benchmark/align_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "gridslam/benchmark/key_map_catalog.hpp"
#include "gridslam/common/angles.hpp"
#include "gridslam/description/keymap_describer.hpp"

namespace gridslam::benchmark {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double Median(std::vector<double> values) {
  if (values.empty()) {
    return kNaN;
  }
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) {
    return *middle;
  }
  const double upper = *middle;
  return 0.5 * (upper + *std::max_element(values.begin(), middle));
}

double Ratio(long numerator, long denominator) {
  return denominator > 0 ? static_cast<double>(numerator) / static_cast<double>(denominator) : kNaN;
}

struct Described {
  description::KeyMapDescription description;
  double seconds = 0.0;
};

PairOutcome AlignPair(const TestPair& pair, bool positive, const Described& a, const Described& b,
                      const AlignEvalConfig& config) {
  PairOutcome outcome;
  outcome.pair = pair;
  outcome.positive = positive;
  outcome.features_a = a.description.features.size();
  outcome.features_b = b.description.features.size();
  const matching::VerificationInput verification =
      description::KeyMapDescription::Verification(a.description, b.description);
  auto start = Clock::now();
  const matching::AlignResult result = matching::Align(
      a.description.features, b.description.features, config.matching, &verification);
  outcome.seconds_align = SecondsSince(start);
  outcome.accepted = result.accepted;
  outcome.reason = result.reason;
  outcome.T_a_b_aligned = result.T_a_b;
  outcome.T_a_b = result.T_a_b;
  outcome.matches = static_cast<int>(result.matches.size());
  outcome.inliers = static_cast<int>(result.inliers.size());
  outcome.agreement = result.agreement;
  outcome.contradiction = result.contradiction;
  if (result.accepted && config.refinement.enabled) {
    start = Clock::now();
    const loop_closure::RefinementResult refined = loop_closure::RefineOnDistanceField(
        b.description.obstacle_points, a.description.distance, result.T_a_b, config.refinement);
    outcome.seconds_refine = SecondsSince(start);
    if (refined.ok) {
      outcome.T_a_b = refined.T_a_b;
      outcome.refined = true;
    }
  }
  {
    const Pose2 error = Between(pair.T_a_b_true, outcome.T_a_b);
    const Pose2 error_aligned = Between(pair.T_a_b_true, outcome.T_a_b_aligned);
    outcome.error_translation = error.translation().norm();
    outcome.error_rotation = std::abs(NormalizeAngle(error.theta()));
    outcome.error_translation_aligned = error_aligned.translation().norm();
    outcome.error_rotation_aligned = std::abs(NormalizeAngle(error_aligned.theta()));
    const double max_rotation = DegToRad(config.eval.correct_rotation_deg);
    outcome.correct = outcome.accepted &&
                      outcome.error_translation < config.eval.correct_translation &&
                      outcome.error_rotation < max_rotation;
    // Negatives: an accepted alignment is false unless it lands near the (approximate) truth, as
    // it may for two far-apart key maps whose windows still share a corner.
    outcome.gross =
        outcome.accepted && (outcome.error_translation > config.eval.gross_translation ||
                             outcome.error_rotation > DegToRad(config.eval.gross_rotation_deg));
  }
  return outcome;
}

bool WithinLimits(const PairOutcome& o, const AlignEvalOptions& options) {
  return o.error_translation_aligned < options.correct_translation &&
         o.error_rotation_aligned < DegToRad(options.correct_rotation_deg);
}

/// Runs the front end again over `frames` (it is deterministic) and describes the key maps
/// marked in `needed` as they are finished, so only those are kept. Runtime error if the second
/// run hands out other key maps than `catalog` holds.
Result<std::vector<std::optional<Described>>> DescribeKeyMaps(
    std::span<const Frame> frames, const scan_matching::FrontEndOptions& front_end,
    const KeyMapCatalog& catalog, const std::vector<char>& needed,
    const description::DescriptionOptions& options) {
  std::vector<std::optional<Described>> described(catalog.KeyMaps().size());
  if (std::find(needed.begin(), needed.end(), 1) == needed.end()) {
    return described;
  }
  const description::KeyMapDescriber describer(options);
  bool deterministic = true;
  const KeyMapCatalog again =
      KeyMapCatalog::Build(frames, front_end, [&](keymap::KeyMap&& key_map) {
        const auto id = static_cast<std::size_t>(key_map.id);
        if (id >= needed.size() ||
            !IsApprox(key_map.T_odom_key, catalog.KeyMaps()[id].T_odom_key)) {
          deterministic = false;
          return;
        }
        if (needed[id] == 0) {
          return;
        }
        const auto start = Clock::now();
        Described d{describer.Describe(key_map), 0.0};
        d.seconds = SecondsSince(start);
        described[id] = std::move(d);
      });
  if (!deterministic || again.KeyMaps().size() != catalog.KeyMaps().size()) {
    return RuntimeError(
        "align-eval: the front end handed out different key maps on its second run over the "
        "log (it must be deterministic)");
  }
  return described;
}

/// Features per key map and description time over the described key maps.
void AddDescriptionStats(const std::vector<std::optional<Described>>& described,
                         AlignEvalSummary* summary) {
  std::vector<double> features;
  double seconds = 0.0;
  double seconds_distance = 0.0;
  double seconds_features = 0.0;
  for (const auto& d : described) {
    if (d) {
      features.push_back(d->description.features.size());
      seconds += d->seconds;
      seconds_distance += d->description.seconds_distance;
      seconds_features += d->description.seconds_features;
    }
  }
  summary->described = static_cast<long>(features.size());
  const auto n = static_cast<double>(features.size());
  double total = 0.0;
  for (const double f : features) {
    total += f;
  }
  summary->features_per_keymap = features.empty() ? kNaN : total / n;
  summary->features_median = Median(features);
  summary->ms_per_keymap = features.empty() ? kNaN : 1e3 * seconds / n;
  summary->ms_distance_per_keymap = features.empty() ? kNaN : 1e3 * seconds_distance / n;
  summary->ms_features_per_keymap = features.empty() ? kNaN : 1e3 * seconds_features / n;
}

}  // namespace

AlignEvalSummary Summarize(std::span<const PairOutcome> positives,
                           std::span<const PairOutcome> negatives) {
  AlignEvalSummary s;
  std::vector<double> errors_m;
  std::vector<double> errors_deg;
  std::vector<double> aligned_m;
  std::vector<double> aligned_deg;
  std::vector<double> align_ms;
  double refine_seconds = 0.0;
  long refined = 0;
  for (const PairOutcome& o : positives) {
    ++s.pairs;
    s.accepted += o.accepted ? 1 : 0;
    s.gross_wrong += o.gross ? 1 : 0;
    if (o.correct) {
      ++s.correct;
      errors_m.push_back(o.error_translation);
      errors_deg.push_back(RadToDeg(o.error_rotation));
      aligned_m.push_back(o.error_translation_aligned);
      aligned_deg.push_back(RadToDeg(o.error_rotation_aligned));
    }
    if (!o.accepted) {
      ++s.rejected[matching::ToString(o.reason)];
    }
  }
  for (const PairOutcome& o : negatives) {
    ++s.negatives;
    s.negatives_accepted += o.accepted ? 1 : 0;
    s.false_accepts += o.gross ? 1 : 0;
  }
  for (const auto* set : {&positives, &negatives}) {
    for (const PairOutcome& o : *set) {
      align_ms.push_back(1e3 * o.seconds_align);
      if (o.refined || o.seconds_refine > 0.0) {
        refine_seconds += o.seconds_refine;
        ++refined;
      }
    }
  }
  s.wrong = s.accepted - s.correct;
  s.precision = Ratio(s.correct, s.accepted);
  s.recall = Ratio(s.correct, s.pairs);
  s.median_error_m = Median(errors_m);
  s.median_error_deg = Median(errors_deg);
  s.median_error_aligned_m = Median(aligned_m);
  s.median_error_aligned_deg = Median(aligned_deg);
  double total_ms = 0.0;
  for (const double ms : align_ms) {
    total_ms += ms;
  }
  s.ms_per_pair = align_ms.empty() ? kNaN : total_ms / static_cast<double>(align_ms.size());
  s.ms_per_pair_median = Median(align_ms);
  s.ms_refine_per_accept = refined > 0 ? 1e3 * refine_seconds / static_cast<double>(refined) : kNaN;
  return s;
}

Result<AlignEvalReport> RunAlignEval(const AlignEvalInput& input, const AlignEvalConfig& config) {
  for (const Status& s :
       {config.front_end.Validate(), config.description.Validate(), config.matching.Validate(),
        config.refinement.Validate(), config.eval.Validate()}) {
    if (!s.ok()) {
      return s.error();
    }
  }
  if (input.frames.empty()) {
    return InvalidInput("align-eval: the log has no laser scans");
  }
  // The front end does not need the scans' ranges in its key maps here.
  scan_matching::FrontEndOptions front_end = config.front_end;
  front_end.keymap.keep_scans = false;

  // Pass 1: the key maps' frames and scans, then the pairs to test.
  const KeyMapCatalog catalog = KeyMapCatalog::Build(input.frames, front_end);
  AlignEvalReport report;
  report.frames = static_cast<long>(catalog.Frames().size());
  report.key_maps = static_cast<long>(catalog.KeyMaps().size());
  report.seconds_front_end = catalog.Seconds();
  PositiveSelection positives =
      SelectPositives(catalog, input.relations, config.eval, config.relations_in_laser_frame);
  const NegativeSelection negatives = SelectNegatives(catalog, input.ground_truth, config.eval);
  report.negative_candidates = negatives.candidates;
  report.negatives_from_ground_truth = negatives.from_ground_truth;

  // Pass 2: the key maps of the pairs, described.
  std::vector<char> needed(catalog.KeyMaps().size(), 0);
  const std::vector<TestPair>& positive_pairs = positives.pairs;
  for (const std::vector<TestPair>* pairs : {&positive_pairs, &negatives.pairs}) {
    for (const TestPair& pair : *pairs) {
      needed[static_cast<std::size_t>(pair.key_a)] = 1;
      needed[static_cast<std::size_t>(pair.key_b)] = 1;
    }
  }
  auto described = DescribeKeyMaps(input.frames, front_end, catalog, needed, config.description);
  if (!described.ok()) {
    return described.error();
  }

  // Alignment of every pair from the precomputed descriptions.
  auto align_all = [&](const std::vector<TestPair>& pairs, bool positive) {
    std::vector<PairOutcome> outcomes;
    outcomes.reserve(pairs.size());
    for (const TestPair& pair : pairs) {
      outcomes.push_back(
          AlignPair(pair, positive, *described.value()[static_cast<std::size_t>(pair.key_a)],
                    *described.value()[static_cast<std::size_t>(pair.key_b)], config));
    }
    return outcomes;
  };
  report.positives = align_all(positives.pairs, true);
  report.negatives = align_all(negatives.pairs, false);
  positives.pairs.clear();
  report.selection = std::move(positives);

  AlignEvalSummary& summary = report.summary;
  summary = Summarize(report.positives, report.negatives);
  summary.correct_aligned = std::count_if(
      report.positives.begin(), report.positives.end(),
      [&](const PairOutcome& o) { return o.accepted && WithinLimits(o, config.eval); });
  AddDescriptionStats(described.value(), &summary);
  return report;
}

}  // namespace gridslam::benchmark
