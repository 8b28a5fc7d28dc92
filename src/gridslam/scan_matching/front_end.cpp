#include "gridslam/scan_matching/front_end.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "gridslam/common/angles.hpp"
#include "gridslam/common/check.hpp"
#include "gridslam/common/logging.hpp"
#include "gridslam/scan_matching/correlative_search.hpp"

namespace gridslam::scan_matching {
namespace {

using Clock = std::chrono::steady_clock;

// A refinement from another start replaces the current best only when it scores this much
// better (fraction of points on the map), as in ScanMatcher::Match.
constexpr double kScoreMargin = 0.05;
// Two refinements this close converged to the same optimum (a few cells, half a degree).
constexpr double kSamePoseXy = 0.1;
constexpr double kSamePoseTheta = 0.01;
// The constant-velocity prediction is a guess, not a measurement: it carries no degenerate
// direction of a match (scan_matcher.hpp).
constexpr PriorKind kModel = PriorKind::kMotionModel;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The yaw correction the scan alone asks for. The match balances the scan against the prior, so
// its correction shrinks as the prior tightens; fed back into the prior's scale that would
// ratchet the prior ever tighter until systematic odometry errors pass unchecked. With the
// posterior information H = H_scan + H_prior (the match's covariance includes the prior), the
// scan's own optimum lies at H_scan^-1 H (x - prior) from the prior, to first order.
double PriorFreeYawCorrection(const MatchResult& match, const Pose2& prior,
                              const Eigen::Matrix3d& prior_information) {
  const Eigen::Vector3d correction(match.T_odom_base.x() - prior.x(),
                                   match.T_odom_base.y() - prior.y(),
                                   NormalizeAngle(match.T_odom_base.theta() - prior.theta()));
  const Eigen::Matrix3d posterior = match.covariance.inverse();
  const Eigen::Matrix3d scan = posterior - prior_information;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(scan);
  if (!posterior.allFinite() || ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
    return correction.z();
  }
  const Eigen::Vector3d free = ldlt.solve(posterior * correction);
  return free.allFinite() ? free.z() : correction.z();
}

}  // namespace

const char* ToString(FrameStatus status) {
  switch (status) {
    case FrameStatus::kFirst:
      return "first";
    case FrameStatus::kMatched:
      return "matched";
    case FrameStatus::kOdometryOnly:
      return "odometry_only";
    case FrameStatus::kFallbackFewPoints:
      return "fallback_few_points";
    case FrameStatus::kFallbackEmptyMap:
      return "fallback_empty_map";
    case FrameStatus::kFallbackRejected:
      return "fallback_rejected";
  }
  return "unknown";
}

Status FrontEndOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(local_map.Validate());
  GRIDSLAM_RETURN_IF_ERROR(matcher.Validate());
  GRIDSLAM_RETURN_IF_ERROR(keymap.Validate());
  GRIDSLAM_RETURN_IF_ERROR(
      Require(insert_distance >= 0.0 && insert_angle >= 0.0 && insert_period >= 0.0,
              "front_end insert thresholds >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(
      odometry_sigma_forward > 0.0 && odometry_sigma_lateral > 0.0 && odometry_sigma_theta > 0.0,
      "front_end odometry sigmas > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(odometry_drift_xy >= 0.0 && odometry_drift_theta >= 0.0,
                                   "front_end odometry drifts >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(adaptive_window > 0 && adaptive_min_scale > 0.0 && adaptive_min_scale <= 1.0,
              "front_end.adaptive_window > 0, 0 < adaptive_min_scale <= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(odometry_check.Valid(),
                                   "front_end.odometry_check: window > 0, sigmas > 0, floors > 0, "
                                   "velocity_baseline > 0, max_acceleration > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(
      wide_search.linear_window >= 0.0 && wide_search.linear_step >= 1 &&
          wide_search.angular_window >= 0.0 && wide_search.angular_step > 0.0 &&
          wide_search.sigma > 0.0 && wide_search.max_points >= 3 && wide_search.candidates >= 1,
      "front_end.wide_search: windows >= 0, steps > 0, sigma > 0, max_points >= 3, "
      "candidates >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(poor_match.Validate());
  GRIDSLAM_RETURN_IF_ERROR(Require(max_correction_xy > 0.0 && max_correction_theta > 0.0,
                                   "front_end max corrections > 0"));
  return Status::Ok();
}

FrontEnd::FrontEnd(const FrontEndOptions& options)
    : options_(options),
      matcher_(options.matcher),
      field_(options.matcher.max_correspondence_distance),
      matching_field_(options.matcher.max_correspondence_distance),
      keymaps_(options.keymap),
      odometry_noise_(options.adaptive_window, options.adaptive_min_scale),
      motion_check_(options.odometry_check),
      score_monitor_(options.poor_match) {
  GRIDSLAM_CHECK(options.Validate().ok()) << options.Validate().error().ToString();
}

FrontEnd::~FrontEnd() = default;

FrontEnd::PriorSigmas FrontEnd::DefaultPriorSigmas(const Pose2& odometry_increment) const {
  // Independent errors along and across the robot's heading, and in yaw, each a floor plus a
  // part proportional to the motion.
  const double travelled = odometry_increment.translation().norm();
  return {options_.odometry_sigma_forward + options_.odometry_drift_xy * travelled,
          options_.odometry_sigma_lateral + options_.odometry_drift_xy * travelled,
          options_.odometry_sigma_theta +
              options_.odometry_drift_theta * std::abs(odometry_increment.theta())};
}

Eigen::Matrix3d FrontEnd::PriorInformation(const PriorSigmas& defaults,
                                           const Pose2& T_odom_base_predicted,
                                           bool odometry_trusted) const {
  // The yaw default scaled to the odometry at hand (not to a constant-velocity guess); rotated
  // into the odometry frame.
  const double forward = defaults.forward;
  const double lateral = defaults.lateral;
  const double sigma_theta =
      (options_.adaptive_odometry && odometry_trusted ? odometry_noise_.RotationScale() : 1.0) *
      defaults.theta;
  const Eigen::Matrix2d R = T_odom_base_predicted.Rotation();
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  information.topLeftCorner<2, 2>() =
      R * Eigen::Vector2d(1.0 / (forward * forward), 1.0 / (lateral * lateral)).asDiagonal() *
      R.transpose();
  information(2, 2) = 1.0 / (sigma_theta * sigma_theta);
  return information;
}

bool FrontEnd::ShouldInsert(const Frame& frame, const Pose2& pose) const {
  const Pose2 moved = Between(last_insert_pose_, pose);
  return moved.translation().norm() >= options_.insert_distance ||
         std::abs(moved.theta()) >= options_.insert_angle ||
         std::abs(ToSeconds(frame.corrected_time - last_insert_time_)) >= options_.insert_period;
}

const MatchingField& FrontEnd::NearField() {
  const auto start = Clock::now();
  field_.Update(*window_);
  window_->ClearChanges();
  stats_.seconds_field += SecondsSince(start);
  return field_;
}

MatchResult FrontEnd::MatchInWindows(const ScanPoints& points, const Pose2& start,
                                     const Pose2& prior, const Eigen::Matrix3d& information,
                                     PriorKind kind, bool refine_only, WindowPolicy policy) {
  auto match = [&](const RollingWindow& window, const MatchingField& field) {
    return refine_only ? matcher_.Refine(window, field, points, start, prior, information, kind)
                       : matcher_.Match(window, field, points, prior, information, kind);
  };
  auto match_far = [&]() {
    // The matching window's field is brought up to date only when a match needs it (it follows
    // the window's changes since the last time, or is rebuilt).
    const auto start_time = Clock::now();
    matching_field_.Update(*matching_window_);
    matching_window_->ClearChanges();
    stats_.seconds_field += SecondsSince(start_time);
    MatchResult far = match(*matching_window_, matching_field_);
    far.far_window = true;
    return far;
  };
  if (matching_window_ == nullptr) {
    return match(*window_, NearField());
  }
  if (policy == WindowPolicy::kMatchingWindow) {
    return match_far();
  }
  MatchResult near = match(*window_, NearField());
  const int near_degenerate = near.degeneracy.degenerate_directions;
  if (near.ok && near_degenerate == 0) {
    return near;
  }
  // The key-map window failed or left a direction to the prior: the returns beyond it may hold
  // what it cannot.
  MatchResult far = match_far();
  const bool better =
      far.ok && (!near.ok || far.degeneracy.degenerate_directions < near_degenerate);
  return better ? far : near;
}

MatchResult FrontEnd::MatchWithoutTrustedOdometry(const ScanPoints& points,
                                                  const MotionPrediction& prediction,
                                                  const Eigen::Matrix3d& velocity_information,
                                                  const Eigen::Matrix3d& odometry_information,
                                                  FrontEndStep* step, bool* velocity_preferred) {
  *velocity_preferred = false;
  const double good = options_.matcher.good_score;
  const Pose2& centre = prediction.constant_velocity;
  if (prediction.check == OdometryCheck::kDoubtful) {
    // The odometry may well be right (a real manoeuvre, or a false alarm): it keeps the frame
    // unless the scan clearly prefers another pose. The constant velocity overrules it only
    // when it explains the scan well, clearly better, and at another pose; a failed or poor
    // match is no evidence against the odometry.
    const MatchResult from_odometry =
        MatchInWindows(points, prediction.odometry, prediction.odometry, odometry_information,
                       PriorKind::kMeasured, false, WindowPolicy::kMatchingWindow);
    const MatchResult from_velocity = MatchInWindows(points, centre, centre, velocity_information,
                                                     kModel, false, WindowPolicy::kMatchingWindow);
    const Pose2 difference = Between(from_velocity.T_odom_base, from_odometry.T_odom_base);
    const bool same = difference.translation().norm() < kSamePoseXy &&
                      std::abs(difference.theta()) < kSamePoseTheta;
    // Both matches search the same small region around their own prediction, so their scores
    // compare like for like: the better explained pose wins by a clear margin, whatever the
    // scene's usual score (a hall's returns fit worse than an office's everywhere).
    // An impossible increment (faster than traction allows) is a glitch: there the burden of
    // proof turns, and the constant velocity keeps the frame unless the odometry's pose explains
    // the scan clearly better (a corridor explains both alike).
    const bool overrule =
        from_velocity.ok && !same &&
        (prediction.impossible
             ? !(from_odometry.ok && from_odometry.score > from_velocity.score + kScoreMargin)
             : (!from_odometry.ok || from_velocity.score > from_odometry.score + kScoreMargin));
    *velocity_preferred = overrule;
    // No wide search here: the robot moved smoothly even if its odometry jumped, so the pose is
    // near the constant velocity, whose match already searches around it (±0.3 m, ±0.25 rad).
    // A wide search against a doubtful odometry found look-alike poses a metre sideways in
    // halls the scan barely constrains (fr-clinic).
    return overrule ? from_velocity : from_odometry;
  }
  MatchResult best = MatchInWindows(points, centre, centre, velocity_information, kModel, false,
                                    WindowPolicy::kNearFirst);
  if ((best.ok && best.score >= good) || !options_.wide_search.enabled) {
    return best;
  }
  // A lattice pose replaces the match if it explains the scan well and clearly better.
  const WideRefinements wide =
      WideSearch(points, centre, velocity_information, WindowPolicy::kNearFirst, step);
  for (const MatchResult& refined : wide.matches) {
    if (refined.score >= good && (!best.ok || refined.score > best.score + kScoreMargin)) {
      best = refined;
    }
  }
  return best;
}

FrontEnd::WideRefinements FrontEnd::WideSearch(const ScanPoints& points, const Pose2& centre,
                                               const Eigen::Matrix3d& information,
                                               WindowPolicy policy, FrontEndStep* step) {
  const WideSearchOptions& wide = options_.wide_search;
  SearchLattice lattice;
  lattice.linear_window = wide.linear_window;
  lattice.linear_step = wide.linear_step;
  lattice.angular_window = wide.angular_window;
  lattice.angular_step = wide.angular_step;
  lattice.sigma = wide.sigma;
  lattice.max_points = static_cast<std::size_t>(wide.max_points);
  // The lattice is scored on the field of the first window the refinements use (the matching
  // window's is up to date once a match has used it).
  const bool far = policy == WindowPolicy::kMatchingWindow && matching_window_ != nullptr;
  const MatchingField& field = far ? matching_field_ : NearField();
  WideRefinements result;
  result.separation_xy = 2.0 * wide.linear_step * field.Limits().Resolution();
  result.separation_theta = 2.0 * wide.angular_step;
  const std::vector<SearchResult> starts =
      CorrelativeSearchTop(field, points, centre, lattice, wide.candidates, result.separation_xy,
                           result.separation_theta);
  step->wide_search = true;
  ++stats_.wide_searches;
  for (const SearchResult& start : starts) {
    // The prior moves with the start: the prediction is no better than the lattice pose the
    // scan prefers. A pose far from the prediction must explain the scan well.
    MatchResult refined = MatchInWindows(points, start.T_odom_base, start.T_odom_base, information,
                                         kModel, true, policy);
    if (refined.ok) {
      refined.searched = true;
      result.matches.push_back(refined);
    }
  }
  return result;
}

MatchResult FrontEnd::RescuePoorMatch(const ScanPoints& points, const Pose2& predicted,
                                      const Eigen::Matrix3d& information, const MatchResult& poor,
                                      FrontEndStep* step) {
  const WideRefinements wide =
      WideSearch(points, predicted, information, WindowPolicy::kMatchingWindow, step);
  // A pose that is to overrule the odometry must be unambiguous too: no other pose the search
  // found (a look-alike along a corridor, in a hall of few returns) may explain the scan about
  // as well.
  std::vector<ScoredPose> candidates;
  candidates.reserve(wide.matches.size());
  for (const MatchResult& r : wide.matches) {
    candidates.push_back({r.T_odom_base, r.score});
  }
  RescueRule rule;
  rule.good_score = options_.matcher.good_score;
  rule.margin = kScoreMargin;
  rule.separation_xy = wide.separation_xy;
  rule.separation_theta = wide.separation_theta;
  rule.window_xy = options_.wide_search.linear_window;
  rule.window_theta = options_.wide_search.angular_window;
  const RescueChoice choice =
      score_monitor_.Choose(candidates, predicted, poor.ok ? poor.score : -1.0, rule);
  stats_.poor_ambiguous += choice.verdict == RescueVerdict::kAmbiguous ? 1 : 0;
  step->rescue = choice.verdict;
  if (choice.has_rival) {
    const Pose2 d = Between(candidates[choice.best].pose, candidates[choice.rival].pose);
    GRIDSLAM_LOG_DEBUG(
        "poor match {:.2f}: wide search best {:.2f}, {}; rival {:.2f} at {:.3f} {:.3f} {:.3f}",
        poor.ok ? poor.score : 0.0, candidates[choice.best].score, ToString(choice.verdict),
        candidates[choice.rival].score, d.x(), d.y(), d.theta());
  }
  return choice.verdict == RescueVerdict::kRescued ? wide.matches[choice.best] : poor;
}

FrontEndStep FrontEnd::AddFrame(const Frame& frame) {
  FrontEndStep step;
  step.time = frame.time;
  ++stats_.frames;
  auto start = Clock::now();
  NormalEstimation normals;
  normals.grazing_normals = options_.local_map.grazing_normals;
  // The wall normals once the laser has measured noisy (laser_noise_monitor.hpp).
  const bool noisy = laser_noise_.Above(options_.local_map.WallNormalNoise());
  normals.max_angle_sigma = noisy ? options_.local_map.normal_angle_sigma : 0.0;
  const ScanPoints points =
      ExtractScanPoints(frame.scan, frame.T_base_laser, options_.local_map.max_range, normals);
  laser_noise_.Add(points.surface_noise);
  step.wall_normals = !points.wall_normals.empty();
  stats_.wall_normal_frames += step.wall_normals ? 1 : 0;
  stats_.seconds_preprocess += SecondsSince(start);

  const std::optional<Pose2> odometry =
      frame.has_odometry ? std::optional<Pose2>(frame.T_odom_base) : std::nullopt;
  Pose2 pose = frame.has_odometry ? frame.T_odom_base : Pose2();
  const bool first = window_ == nullptr;
  MotionPrediction prediction;
  if (first) {
    const bool point_to_line = options_.matcher.residual == "point_to_line";
    const bool separate = options_.local_map.MatchingSize() > options_.local_map.size;
    window_ = std::make_unique<RollingWindow>(options_.local_map, pose.translation(),
                                              point_to_line && !separate);
    if (separate) {
      matching_window_ = std::make_unique<RollingWindow>(options_.local_map.MatchingWindow(),
                                                         pose.translation(), point_to_line);
    }
    step.status = FrameStatus::kFirst;
    motion_check_.Reset(frame.corrected_time, pose, pose);
  } else {
    prediction = motion_check_.Predict(frame.corrected_time, odometry);
    step.odometry = prediction.check;
    // The raw-odometry baseline (match off) follows the odometry, glitches included.
    const bool missing = prediction.check == OdometryCheck::kMissing && options_.match;
    const bool trusted = prediction.check == OdometryCheck::kConsistent || !options_.match;
    stats_.odometry_doubtful += prediction.check == OdometryCheck::kDoubtful ? 1 : 0;
    stats_.odometry_missing += prediction.check == OdometryCheck::kMissing ? 1 : 0;
    // A doubtful odometry keeps its prior unless the scan overrules it; a missing one has the
    // constant velocity instead.
    const Pose2 predicted = missing ? prediction.constant_velocity : prediction.odometry;
    const PriorSigmas defaults = DefaultPriorSigmas(missing ? Between(last_estimate_, predicted)
                                                            : prediction.odometry_increment);
    const Eigen::Matrix3d prior_information = PriorInformation(defaults, predicted, !missing);
    pose = predicted;
    step.covariance = prior_information.inverse();
    if (!options_.match) {
      step.status = FrameStatus::kOdometryOnly;
    } else if (static_cast<int>(points.size()) < options_.matcher.min_points) {
      step.status = FrameStatus::kFallbackFewPoints;
      ++stats_.fallback_few_points;
    } else if (MatchingWindow()->NumObstacles() < options_.matcher.min_correspondences) {
      step.status = FrameStatus::kFallbackEmptyMap;
      ++stats_.fallback_empty_map;
    } else {
      start = Clock::now();
      bool velocity_preferred = false;
      bool rescued = false;
      const Eigen::Matrix3d velocity_information = PriorInformation(
          DefaultPriorSigmas(Between(last_estimate_, prediction.constant_velocity)),
          prediction.constant_velocity, false);
      if (trusted) {
        step.match = MatchInWindows(points, predicted, predicted, prior_information,
                                    PriorKind::kMeasured, false, WindowPolicy::kMatchingWindow);
      } else {
        step.match = MatchWithoutTrustedOdometry(points, prediction, velocity_information,
                                                 prior_information, &step, &velocity_preferred);
      }
      // A poor match with odometry: the prediction may be wrong although it looked plausible
      // (odometry reporting forward motion while the robot reverses). The wide search around it
      // may find a pose that explains the scan clearly better, and as well as the recent
      // matches did; that pose overrules the odometry.
      if (!missing && options_.poor_match.enabled && options_.wide_search.enabled &&
          score_monitor_.Poor(step.match.ok ? step.match.score : 0.0)) {
        step.poor_match = true;
        ++stats_.poor_matches;
        step.match = RescuePoorMatch(points, predicted, velocity_information, step.match, &step);
        rescued = step.rescue == RescueVerdict::kRescued;
        stats_.poor_rescued += rescued ? 1 : 0;
        velocity_preferred = velocity_preferred && !rescued;
      }
      stats_.seconds_match += SecondsSince(start);
      stats_.searches += step.match.searched ? 1 : 0;
      // Trusted odometry: the match may correct the prediction by the usual limits. Otherwise
      // it may also land anywhere the wide search looks around the constant velocity; a pose
      // beyond the usual limits of the odometry's prediction overrules a doubtful increment.
      auto within = [](const Pose2& from, const Pose2& to, double xy, double theta) {
        const Pose2 d = Between(from, to);
        return d.translation().norm() <= xy && std::abs(d.theta()) <= theta;
      };
      const Pose2& found = step.match.T_odom_base;
      const bool near_prediction = !missing && within(predicted, found, options_.max_correction_xy,
                                                      options_.max_correction_theta);
      // Against a doubtful odometry, only a match that explains the scan well, or clearly better
      // than the odometry's prediction does, may leave the odometry's limits; a poor one (a hall
      // the scan barely constrains) keeps the odometry.
      const bool evidence =
          missing || velocity_preferred || step.match.score >= options_.matcher.good_score;
      const bool near_velocity =
          !trusted && evidence &&
          within(prediction.constant_velocity, found,
                 std::max(options_.max_correction_xy,
                          std::sqrt(2.0) * options_.wide_search.linear_window),
                 std::max(options_.max_correction_theta, options_.wide_search.angular_window));
      step.odometry_overruled = rescued || (prediction.check == OdometryCheck::kDoubtful &&
                                            step.match.ok && !near_prediction && near_velocity);
      stats_.odometry_overruled += step.odometry_overruled ? 1 : 0;
      if (step.match.ok && (near_prediction || near_velocity || rescued)) {
        pose = step.match.T_odom_base;
        step.covariance = step.match.covariance;
        step.status = FrameStatus::kMatched;
        ++stats_.matched;
        stats_.degenerate_one += step.match.degeneracy.degenerate_directions == 1 ? 1 : 0;
        stats_.degenerate_both += step.match.degeneracy.degenerate_directions == 2 ? 1 : 0;
        stats_.far_matches += step.match.far_window ? 1 : 0;
        score_monitor_.Add(step.match.score);
        // A doubtful increment the scan did not overrule was matched with the odometry's prior:
        // its correction is a sample of the odometry's noise like any other.
        if (!missing && !step.odometry_overruled) {
          odometry_noise_.Add(PriorFreeYawCorrection(step.match, predicted, prior_information),
                              defaults.theta);
        }
        // The laser's mounting: increments that a trusted odometry and a good match constraining
        // every direction agree are the robot's motion.
        if (prediction.check == OdometryCheck::kConsistent && !step.odometry_overruled &&
            step.match.degeneracy.degenerate_directions == 0 &&
            step.match.score >= options_.matcher.good_score) {
          mounting_.Add(prediction.odometry_increment, Between(last_estimate_, pose));
        }
      } else {
        step.status = FrameStatus::kFallbackRejected;
        step.odometry_overruled = false;
        ++stats_.fallback_rejected;
      }
    }
    // Every doubtful or missing increment at debug level, every frame at trace level.
    if (prediction.check != OdometryCheck::kConsistent ||
        spdlog::should_log(spdlog::level::trace)) {
      const Pose2 moved = Between(last_estimate_, pose);
      const Pose2& odo = prediction.odometry_increment;
      spdlog::log(
          prediction.check != OdometryCheck::kConsistent ? spdlog::level::debug
                                                         : spdlog::level::trace,
          "frame {}: odometry {} (innovation {:.3f} m {:.3f} rad, thresholds {:.3f} {:.3f}), "
          "{}, {} score {:.2f} ({} degenerate), moved {:.3f} {:.3f} {:.3f}, odometry {:.3f} "
          "{:.3f} {:.3f}",
          stats_.frames - 1, ToString(prediction.check), prediction.innovation_xy,
          prediction.innovation_theta, motion_check_.ThresholdXy(), motion_check_.ThresholdTheta(),
          step.odometry_overruled ? "overruled" : "kept", ToString(step.status), step.match.score,
          step.match.degeneracy.degenerate_directions, moved.x(), moved.y(), moved.theta(), odo.x(),
          odo.y(), odo.theta());
    }
    motion_check_.Update(frame.corrected_time, odometry, pose, prediction, step.odometry_overruled);
  }
  step.T_odom_base = pose;

  start = Clock::now();
  window_->Recentre(pose.translation());
  if (matching_window_ != nullptr) {
    matching_window_->Recentre(pose.translation());
  }
  if (first || ShouldInsert(frame, pose)) {
    window_->InsertScan(pose, points);
    if (matching_window_ != nullptr) {
      matching_window_->InsertScan(pose, points);
    }
    last_insert_pose_ = pose;
    last_insert_time_ = frame.corrected_time;
    step.inserted = true;
    ++stats_.insertions;
  }
  stats_.seconds_insert += SecondsSince(start);

  start = Clock::now();
  keymaps_.AddScan(frame, pose);
  step.key_map = keymaps_.MaybeSnapshot(*window_);
  stats_.key_maps += step.key_map ? 1 : 0;
  stats_.seconds_keymap += SecondsSince(start);
  stats_.field_rebuilds = field_.NumRebuilds() + matching_field_.NumRebuilds();
  stats_.field_tile_updates = field_.NumTileUpdates() + matching_field_.NumTileUpdates();

  last_estimate_ = pose;
  return step;
}

std::optional<keymap::KeyMap> FrontEnd::Finish() {
  if (window_ == nullptr) {
    return std::nullopt;
  }
  auto key = keymaps_.Finish(*window_);
  stats_.key_maps += key ? 1 : 0;
  return key;
}

}  // namespace gridslam::scan_matching
