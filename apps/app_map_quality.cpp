#include "app_map_quality.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "gridslam/io/png_codec.hpp"
#include "gridslam/quality/local_confirmation.hpp"
#include "gridslam/quality/loop_residuals.hpp"
#include "gridslam/quality/map_self_check.hpp"
#include "gridslam/quality/quality_image.hpp"

#include "app_memory.hpp"

namespace gridslam::app {

QualityScans::QualityScans(const quality::SelfCheckOptions& options, int num_robots)
    : options_(options),
      kept_(static_cast<std::size_t>(num_robots)),
      last_(static_cast<std::size_t>(num_robots)) {}

void QualityScans::Add(int robot, long index, const Frame& frame) {
  if (!options_.enabled) {
    return;
  }
  auto& last = last_[static_cast<std::size_t>(robot)];
  if (frame.has_odometry && last.has_value()) {
    const Pose2 delta = last->Inverse() * frame.T_odom_base;
    if (delta.translation().norm() < 0.5 * options_.min_motion &&
        std::abs(NormalizeAngle(delta.theta())) < 0.5 * options_.min_rotation) {
      return;
    }
  }
  last = frame.T_odom_base;
  kept_[static_cast<std::size_t>(robot)].push_back({index, frame.T_base_laser, frame.scan});
}

Result<QualityOutcome> RunSelfCheck(const std::string& dir, const pipeline::MapperResult& result,
                                    const QualityScans& scans,
                                    const quality::SelfCheckOptions& options,
                                    const fusion::FusionOptions& fusion, int threads,
                                    ImageBuffer* pictures) {
  QualityOutcome outcome;
  ImageBuffer own;
  ImageBuffer& buffer = pictures != nullptr ? *pictures : own;
  if (!options.enabled) {
    outcome.report = {{"enabled", false}};
    return outcome;
  }
  quality::SelfCheckStats total;
  nlohmann::json per_map = nlohmann::json::array();
  for (std::size_t c = 0; c < result.maps.size(); ++c) {
    std::vector<fusion::PosedScan> posed;
    for (std::size_t r = 0; r < result.trajectories.size(); ++r) {
      if (result.component_of_robot[r] != static_cast<int>(c)) {
        continue;
      }
      const auto& trajectory = result.trajectories[r];
      for (const QualityScans::Kept& k : scans.Of(static_cast<int>(r))) {
        if (k.index >= 0 && k.index < static_cast<long>(trajectory.size())) {
          posed.push_back(
              {trajectory[static_cast<std::size_t>(k.index)].T_map_base, k.T_base_laser, &k.scan});
        }
      }
    }
    std::vector<std::vector<std::uint8_t>> confirmed;
    if (options.local_travel > 0.0) {
      confirmed = quality::LocalConfirmation(posed, fusion, options, threads);
    }
    quality::SelfCheckResult check = quality::CheckMap(
        result.maps[c], posed, fusion, options, threads, confirmed.empty() ? nullptr : &confirmed);
    confirmed = {};
    total.Merge(check.stats);
    const std::string name =
        result.maps.size() == 1 ? "map_quality.png" : "map_quality_" + std::to_string(c) + ".png";
    const TiledGrid<float> share = quality::DisagreementShare(check, options, 0.02F, threads);
    check = quality::SelfCheckResult{check.stats, {}, {}};  // the per-cell counts are done
    ReleaseFreedMemory();
    const MapLimits& limits = result.maps[c].Limits();
    cv::Mat image = buffer.Image(limits.Height(), limits.Width(), CV_8UC3);
    quality::RenderQualityImage(result.maps[c], fusion, share, threads, image);
    const std::string path = (std::filesystem::path(dir) / name).string();
    GRIDSLAM_RETURN_IF_ERROR(io::WritePng(path, image, threads));
    per_map.push_back({{"image", name},
                       {"score", check.stats.Score()},
                       {"suspect", check.stats.Suspect(options)},
                       {"verdict", quality::ToString(check.stats.Verdict(options))},
                       {"scans", check.stats.scans},
                       {"returns", check.stats.returns}});
  }
  std::vector<quality::LoopMeasurement> loops;
  for (const pipeline::ClosureRecord& c : result.closures) {
    if (c.outcome == pipeline::ClosureOutcome::kAccepted ||
        c.outcome == pipeline::ClosureOutcome::kJoined) {
      loops.push_back({c.from, c.to, c.T_from_to});
    }
  }
  const quality::LoopResidualStats residuals = quality::LoopResiduals(result.graph, loops);
  const quality::SelfCheckVerdict verdict = total.Verdict(options);
  const bool suspect = total.Suspect(options);
  nlohmann::json by_range = nlohmann::json::array();
  for (int b = 0; b < quality::SelfCheckStats::kRangeBands; ++b) {
    const auto ub = static_cast<std::size_t>(b);
    nlohmann::json band = {{"returns", total.band_returns[ub]}, {"score", total.BandScore(b)}};
    if (ub < quality::SelfCheckStats::kRangeBandEdges.size()) {
      band["below_m"] = quality::SelfCheckStats::kRangeBandEdges[ub];
    }
    by_range.push_back(band);
  }
  outcome.report = {{"score", total.Score()},
                    {"raw_score", total.RawScore()},
                    {"local_score", total.LocalScore()},
                    {"local_travel_m", options.local_travel},
                    {"suspect", suspect},
                    {"verdict", quality::ToString(verdict)},
                    {"suspect_below", options.suspect_below},
                    {"agreement_distance_m", options.agreement_distance},
                    {"contradicting_share", total.Contradiction()},
                    {"mean_distance_m", total.MeanDistance()},
                    {"scans", total.scans},
                    {"returns", total.returns},
                    {"returns_outside_map", total.outside},
                    {"by_range", by_range},
                    {"maps", per_map},
                    {"loop_residuals",
                     {{"closures", residuals.closures},
                      {"median_translation_m", residuals.median_translation},
                      {"max_translation_m", residuals.max_translation},
                      {"median_rotation_deg", residuals.median_rotation * 180.0 / std::numbers::pi},
                      {"max_rotation_deg", residuals.max_rotation * 180.0 / std::numbers::pi}}}};
  char line[320];
  std::snprintf(line, sizeof(line),
                "self-check: score %.3f (%s; %.0f%% of returns confirmed by their neighbourhood, "
                "%.1f%% contradict the map, mean distance %.3f m); loop residuals median %.3f m, "
                "max %.3f m",
                total.Score(),
                verdict == quality::SelfCheckVerdict::kConsistent ? "consistent"
                : verdict == quality::SelfCheckVerdict::kContradicted
                    ? "SUSPECT: the map contradicts its scans"
                    : "SUSPECT: the scans disagree with their neighbours",
                100.0 * total.LocalScore(), 100.0 * total.Contradiction(), total.MeanDistance(),
                residuals.median_translation, residuals.max_translation);
  outcome.summary = line;
  return outcome;
}

}  // namespace gridslam::app
