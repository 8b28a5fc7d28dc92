// `gridslam align-eval LOG RELATIONS [--json] [--detector NAME] [--detect-image distance|grid]
// [--descriptor-image distance|obstacle|grid] [--no-verify] [--no-refine] [--negatives N]
// [--ground-truth FILE] [--max-centre-distance M] [--include-shared] [--no-truth-check]
// [--seed S] [--pairs FILE]`:
// the key-map alignment benchmark (docs/design.md §2, §3.2; benchmark/align_eval.hpp). The flags
// override the `description`, `matching.verification`, `loop_closure.refinement` and
// `align_eval` sections of the configuration. `--pairs FILE` writes one TSV line per tested pair.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "gridslam/benchmark/align_eval.hpp"
#include "gridslam/common/angles.hpp"
#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/relations_io.hpp"
#include "gridslam/io/trajectory_io.hpp"

#include "command.hpp"

namespace gridslam::app {
namespace {

struct AlignEvalArgs {
  std::string log;
  std::string relations;
  bool json = false;
  std::optional<std::string> detector;
  std::optional<std::string> detect_image;
  std::optional<std::string> descriptor_image;
  bool no_verify = false;
  bool no_refine = false;
  std::optional<int> negatives;
  std::optional<std::string> ground_truth;
  std::optional<double> max_centre_distance;
  bool include_shared = false;
  bool no_truth_check = false;
  std::optional<int> seed;
  std::optional<std::string> pairs;
};

/// NaN (an undefined ratio or median) as JSON null.
nlohmann::json Number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

/// Pairs and correct ones per 1 m band of true centre distance.
nlohmann::json RecallByDistance(const std::vector<benchmark::PairOutcome>& positives,
                                double max_distance) {
  nlohmann::json bands = nlohmann::json::array();
  const int n = static_cast<int>(std::ceil(max_distance));
  for (int k = 0; k < n; ++k) {
    long pairs = 0;
    long correct = 0;
    for (const auto& o : positives) {
      if (o.pair.centre_distance >= k && o.pair.centre_distance < k + 1) {
        ++pairs;
        correct += o.correct ? 1 : 0;
      }
    }
    bands.push_back(
        {{"from_m", k},
         {"to_m", k + 1},
         {"pairs", pairs},
         {"correct", correct},
         {"recall",
          Number(pairs > 0 ? static_cast<double>(correct) / static_cast<double>(pairs) : NAN)}});
  }
  return bands;
}

nlohmann::json ToJson(const benchmark::AlignEvalReport& r, const benchmark::AlignEvalConfig& c) {
  const benchmark::AlignEvalSummary& s = r.summary;
  const benchmark::PositiveSelection& p = r.selection;
  return {{"pairs", s.pairs},
          {"accepted", s.accepted},
          {"correct", s.correct},
          {"wrong", s.wrong},
          {"gross_wrong", s.gross_wrong},
          {"precision", Number(s.precision)},
          {"recall", Number(s.recall)},
          {"median_error_m", Number(s.median_error_m)},
          {"median_error_deg", Number(s.median_error_deg)},
          {"correct_unrefined", s.correct_aligned},
          {"median_error_unrefined_m", Number(s.median_error_aligned_m)},
          {"median_error_unrefined_deg", Number(s.median_error_aligned_deg)},
          {"ms_per_pair", Number(s.ms_per_pair)},
          {"ms_per_pair_median", Number(s.ms_per_pair_median)},
          {"ms_refine_per_accept", Number(s.ms_refine_per_accept)},
          {"ms_per_keymap", Number(s.ms_per_keymap)},
          {"ms_distance_per_keymap", Number(s.ms_distance_per_keymap)},
          {"ms_features_per_keymap", Number(s.ms_features_per_keymap)},
          {"negatives", s.negatives},
          {"false_accepts", s.false_accepts},
          {"negatives_accepted", s.negatives_accepted},
          {"negative_candidates", r.negative_candidates},
          {"negatives_from_ground_truth", r.negatives_from_ground_truth},
          {"features_per_keymap", Number(s.features_per_keymap)},
          {"features_median", Number(s.features_median)},
          {"described_keymaps", s.described},
          {"rejected", s.rejected},
          {"recall_by_centre_distance", RecallByDistance(r.positives, c.eval.max_centre_distance)},
          {"selection",
           {{"relations", p.relations},
            {"revisits", p.revisits},
            {"missing_scan", p.missing_scan},
            {"same_keymap", p.same_key_map},
            {"too_far", p.too_far},
            {"shared_window", p.shared},
            {"unreliable_truth", p.unreliable},
            {"unchecked_truth", p.unchecked},
            {"duplicate_pairs", p.duplicates}}},
          {"frames", r.frames},
          {"keymaps", r.key_maps},
          {"front_end_s", r.seconds_front_end},
          {"config",
           {{"detector", c.description.detector},
            {"detect_image", c.description.detect_image},
            {"descriptor_image", c.description.descriptor_image},
            {"verify", c.matching.verification.enabled},
            {"refine", c.refinement.enabled},
            {"max_centre_distance", c.eval.max_centre_distance},
            {"include_shared", c.eval.include_shared},
            {"min_time_gap", c.eval.min_time_gap}}}};
}

void PrintText(const benchmark::AlignEvalReport& r) {
  const benchmark::AlignEvalSummary& s = r.summary;
  std::printf(
      "pairs=%ld accepted=%ld correct=%ld wrong=%ld precision=%.4f recall=%.4f "
      "median_error_m=%.4f median_error_deg=%.3f\n",
      s.pairs, s.accepted, s.correct, s.wrong, s.precision, s.recall, s.median_error_m,
      s.median_error_deg);
  std::printf(
      "negatives=%ld false_accepts=%ld features_per_keymap=%.1f ms_per_keymap=%.2f "
      "ms_per_pair=%.3f keymaps=%ld described=%ld\n",
      s.negatives, s.false_accepts, s.features_per_keymap, s.ms_per_keymap, s.ms_per_pair,
      r.key_maps, s.described);
}

/// A reason as one TSV token ("too few inliers" -> "too_few_inliers").
std::string Token(std::string text) {
  std::replace(text.begin(), text.end(), ' ', '_');
  return text;
}

Status WritePairs(const std::string& path, const benchmark::AlignEvalReport& r) {
  std::string out;  // written atomically at the end (no half file on a full disk)
  out +=
      "# kind key_a key_b t1 t2 centre_distance accepted reason correct error_m error_deg "
      "error_unrefined_m error_unrefined_deg features_a features_b matches inliers agreement "
      "contradiction ms_align relations truth_spread_m truth_spread_deg truth_checks "
      "truth_error_m truth_error_deg\n";
  char line[640];
  for (const auto* set : {&r.positives, &r.negatives}) {
    for (const benchmark::PairOutcome& o : *set) {
      std::snprintf(line, sizeof line,
                    "%s %d %d %s %s %.3f %d %s %d %.4f %.4f %.4f %.4f %d %d %d %d %.3f %.3f "
                    "%.3f %d %.4f %.4f %d %.4f %.4f\n",
                    o.positive ? "positive" : "negative", o.pair.key_a, o.pair.key_b,
                    o.positive ? FormatSeconds(o.pair.t1).c_str() : "-",
                    o.positive ? FormatSeconds(o.pair.t2).c_str() : "-", o.pair.centre_distance,
                    o.accepted ? 1 : 0, Token(matching::ToString(o.reason)).c_str(),
                    o.correct ? 1 : 0, o.error_translation, RadToDeg(o.error_rotation),
                    o.error_translation_aligned, RadToDeg(o.error_rotation_aligned), o.features_a,
                    o.features_b, o.matches, o.inliers, o.agreement, o.contradiction,
                    1e3 * o.seconds_align, o.pair.relations, o.pair.truth_spread_translation,
                    RadToDeg(o.pair.truth_spread_rotation), o.pair.truth_checks,
                    o.pair.truth_error_translation, RadToDeg(o.pair.truth_error_rotation));
      out += line;
    }
  }
  return io::WriteFileAtomically(path, out);
}

int RunAlignEval(const AlignEvalArgs& args, AppContext& context) {
  SlamOptions& options = context.options;
  options.description.detector = args.detector.value_or(options.description.detector);
  options.description.detect_image = args.detect_image.value_or(options.description.detect_image);
  options.description.descriptor_image =
      args.descriptor_image.value_or(options.description.descriptor_image);
  options.matching.verification.enabled = options.matching.verification.enabled && !args.no_verify;
  options.loop_closure.refinement.enabled =
      options.loop_closure.refinement.enabled && !args.no_refine;
  benchmark::AlignEvalOptions& eval = options.align_eval;
  eval.negatives = args.negatives.value_or(eval.negatives);
  eval.max_centre_distance = args.max_centre_distance.value_or(eval.max_centre_distance);
  eval.include_shared = eval.include_shared || args.include_shared;
  eval.seed = args.seed.value_or(eval.seed);
  if (args.no_truth_check) {
    eval.truth_max_error = eval.truth_max_error_deg = std::numeric_limits<double>::infinity();
  }
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  benchmark::AlignEvalConfig config{options.front_end,
                                    options.description,
                                    options.matching,
                                    options.loop_closure.refinement,
                                    eval,
                                    options.eval.trajectory_frame == "laser"};

  io::CarmenStats log_stats;
  auto frames = io::ReadCarmenLog(args.log, options.log, &log_stats);
  if (!frames.ok()) {
    return ReportError(frames.error());
  }
  if (frames.value().empty()) {
    return ReportError(io::NoScansError(args.log, log_stats));
  }
  auto relations = io::ReadRelations(args.relations);
  if (!relations.ok()) {
    return ReportError(relations.error());
  }
  std::vector<io::StampedPose> truth;
  if (args.ground_truth) {
    auto read = io::ReadTrajectory(*args.ground_truth);
    if (!read.ok()) {
      return ReportError(read.error());
    }
    truth = std::move(read.value());
  }
  const auto report = benchmark::RunAlignEval({frames.value(), relations.value(), truth}, config);
  if (!report.ok()) {
    return ReportError(report.error());
  }
  if (args.pairs) {
    if (const Status s = WritePairs(*args.pairs, report.value()); !s.ok()) {
      return ReportError(s.error());
    }
  }
  if (args.json) {
    std::cout << ToJson(report.value(), config).dump(2) << "\n";
  } else {
    PrintText(report.value());
  }
  if (report.value().summary.pairs == 0) {
    std::fprintf(stderr, "gridslam: warning: no relation gave a test pair\n");
  }
  return kExitOk;
}

RunFunction SetupAlignEval(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<AlignEvalArgs>();
  sub.add_option("LOG", args->log, "CARMEN log")->required();
  sub.add_option("RELATIONS", args->relations, "Its relations (t1 t2 x y z roll pitch yaw)")
      ->required();
  sub.add_flag("--json", args->json, "Print one JSON object");
  sub.add_option("--detector", args->detector, "surf, usurf, sift, orb or akaze");
  sub.add_option("--detect-image", args->detect_image, "Detect on: distance or grid");
  sub.add_option("--descriptor-image", args->descriptor_image,
                 "Descriptors on: distance, obstacle or grid");
  sub.add_flag("--no-verify", args->no_verify, "No grid verification");
  sub.add_flag("--no-refine", args->no_refine, "No refinement on the distance field");
  sub.add_option("--negatives", args->negatives,
                 "Random negative pairs (key maps whose true centres are far apart)");
  sub.add_option("--ground-truth", args->ground_truth,
                 "Trajectory (timestamp x y theta) giving the true key-map centres for negatives");
  sub.add_option("--max-centre-distance", args->max_centre_distance,
                 "Overlap criterion: true key-map centres at most this far apart [m]");
  sub.add_flag("--include-shared", args->include_shared,
               "Also test pairs whose local-map windows never separated");
  sub.add_flag("--no-truth-check", args->no_truth_check,
               "Also test pairs where the front end was locally inaccurate");
  sub.add_option("--seed", args->seed, "Seed of the negative-pair draw");
  sub.add_option("--pairs", args->pairs, "Write one TSV line per tested pair to this file");
  return [args](AppContext& ctx) { return RunAlignEval(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "align-eval",
    "Key-map alignment benchmark: revisits aligned without prior (docs/design.md §3.2)",
    SetupAlignEval});

}  // namespace
}  // namespace gridslam::app
