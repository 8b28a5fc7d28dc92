#include "gridslam/scan_matching/scan_matcher.hpp"

#include <numbers>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "gridslam/scan_matching/correlative_search.hpp"
#include "gridslam/scan_matching/internal/synthetic_world.hpp"

namespace gridslam::scan_matching {
namespace {

using internal::SimulateScan;
using internal::TestWorld;

// Poses around the room from which the map is built.
std::vector<Pose2> MapPoses() {
  return {{2.0, 1.0, 0.3},  {5.0, 1.2, 0.0},  {8.0, 2.0, 1.2},  {8.5, 5.5, 2.5},  {5.0, 5.8, 3.0},
          {1.5, 4.0, -1.8}, {4.5, 3.5, -0.7}, {11.5, 3.7, 0.0}, {14.0, 3.8, 3.1}, {6.0, 3.0, 1.6}};
}

// The map built from the scans at MapPoses(), inserted at T_shift * pose: the map of the world
// moved by T_shift.
struct ShiftedMap {
  explicit ShiftedMap(const Pose2& T_shift, double max_distance = 0.3)
      : window(Options(), T_shift * Eigen::Vector2d(6.0, 3.5), true), field(max_distance) {
    for (const Pose2& pose : MapPoses()) {
      const LaserScan scan = SimulateScan(TestWorld(), pose);
      window.InsertScan(T_shift * pose, ExtractScanPoints(scan, Pose2(), 30.0));
    }
    field.Update(window);
  }
  static LocalMapOptions Options() {
    LocalMapOptions options;
    options.size = 20.0;
    return options;
  }
  RollingWindow window;
  MatchingField field;
};

ScanMatcherOptions MatcherOptions(const std::string& residual) {
  ScanMatcherOptions options;
  options.residual = residual;
  return options;
}

class ScanMatcherResidual : public ::testing::TestWithParam<std::string> {};

TEST_P(ScanMatcherResidual, RecoversAKnownShiftOfTheMap) {
  const Pose2 T_shift(0.12, -0.08, 0.04);
  const ShiftedMap map(T_shift);
  const ScanMatcher matcher(MatcherOptions(GetParam()));
  for (const Pose2& truth : {Pose2(3.0, 1.5, 0.2), Pose2(7.0, 3.0, 2.0), Pose2(12.0, 3.6, -0.1)}) {
    // The scan is taken in the world at `truth`; the prior ignores the shift.
    const ScanPoints scan = ExtractScanPoints(SimulateScan(TestWorld(), truth, 361), Pose2(), 30.0);
    const MatchResult result =
        matcher.Match(map.window, map.field, scan, truth, Eigen::Matrix3d::Zero());
    const Pose2 expected = T_shift * truth;
    ASSERT_TRUE(result.ok);
    EXPECT_LT((result.T_odom_base.translation() - expected.translation()).norm(), 0.05)
        << GetParam() << " at " << truth.x() << ", " << truth.y();
    EXPECT_LT(std::abs(NormalizeAngle(result.T_odom_base.theta() - expected.theta())),
              DegToRad(0.3));
    EXPECT_GT(result.score, 0.9);
    EXPECT_GT(result.correspondences, 100);
    // The covariance is symmetric positive definite.
    EXPECT_TRUE(result.covariance.isApprox(result.covariance.transpose()));
    EXPECT_GT(result.covariance.llt().matrixLLT().diagonal().minCoeff(), 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Residuals, ScanMatcherResidual,
                         ::testing::Values("distance_field", "point_to_line"));

TEST(ScanMatcher, CorrelativeSearchRescuesAPoorPrior) {
  const ShiftedMap map(Pose2(0.3, 0.25, -0.15));
  const Pose2 truth(4.0, 2.8, 0.5);
  const Pose2 expected = Pose2(0.3, 0.25, -0.15) * truth;
  const ScanPoints scan = ExtractScanPoints(SimulateScan(TestWorld(), truth, 181), Pose2(), 30.0);
  ScanMatcherOptions options = MatcherOptions("distance_field");
  options.correlative_search = false;
  const MatchResult plain =
      ScanMatcher(options).Match(map.window, map.field, scan, truth, Eigen::Matrix3d::Zero());
  options.correlative_search = true;
  const MatchResult searched =
      ScanMatcher(options).Match(map.window, map.field, scan, truth, Eigen::Matrix3d::Zero());
  EXPECT_FALSE(plain.searched);
  EXPECT_TRUE(searched.searched);
  EXPECT_GE(searched.score, plain.score);
  EXPECT_LT((searched.T_odom_base.translation() - expected.translation()).norm(), 0.05);
  EXPECT_LT(std::abs(NormalizeAngle(searched.T_odom_base.theta() - expected.theta())),
            DegToRad(0.3));
}

TEST(ScanMatcher, TooFewCorrespondencesAreNotOk) {
  const ShiftedMap map{Pose2()};
  ScanPoints scan;
  scan.points = {{1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}};
  scan.normals.assign(3, Eigen::Vector2d::Zero());
  scan.normal_quality.assign(3, 0.0F);
  const MatchResult result =
      ScanMatcher(MatcherOptions("distance_field"))
          .Match(map.window, map.field, scan, Pose2(2.0, 1.0, 0.3), Eigen::Matrix3d::Zero());
  EXPECT_FALSE(result.ok);
}

TEST(ScanMatcher, PriorHoldsAnUnconstrainedDirection) {
  // A map of two parallel walls only (an endless corridor along x): the scan fixes y and yaw,
  // the prior fixes x.
  LocalMapOptions options;
  options.size = 20.0;
  RollingWindow window(options, Eigen::Vector2d::Zero(), false);
  // Walls in the middle of cell rows (a wall on a cell border occupies two rows).
  const std::vector<internal::Segment> corridor = {{{-50.0, -0.975}, {50.0, -0.975}},
                                                   {{-50.0, 1.025}, {50.0, 1.025}}};
  for (double x = -2.0; x <= 2.0; x += 0.5) {
    window.InsertScan(Pose2(x, 0.0, 0.0),
                      ExtractScanPoints(SimulateScan(corridor, Pose2(x, 0.0, 0.0)), Pose2(), 30.0));
  }
  MatchingField field(0.3);
  field.Update(window);
  const ScanPoints scan =
      ExtractScanPoints(SimulateScan(corridor, Pose2(0.0, 0.1, 0.05)), Pose2(), 30.0);
  const Eigen::Matrix3d prior = Eigen::Vector3d(100.0, 100.0, 100.0).asDiagonal();
  const MatchResult result = ScanMatcher(MatcherOptions("distance_field"))
                                 .Match(window, field, scan, Pose2(0.3, 0.0, 0.0), prior);
  ASSERT_TRUE(result.ok);
  // x comes from the prior (0.3; the scan was taken at x = 0), up to the weak pull of the gaps
  // that grazing rays cut into the map's walls.
  EXPECT_GT(result.T_odom_base.x(), 0.2);
  EXPECT_NEAR(result.T_odom_base.y(), 0.1, 0.03);  // from the scan
  EXPECT_NEAR(result.T_odom_base.theta(), 0.05, DegToRad(0.5));
  // The covariance says so: x is far less certain than y.
  EXPECT_GT(result.covariance(0, 0), 10.0 * result.covariance(1, 1));
}

TEST(ScanMatcher, CorridorAxisIsLeftToTheOdometryPrior) {
  // The front end's prior of one scan step (0.09 m, 0.09 rad) against the weak pull of the gaps
  // that grazing rays cut into a corridor's walls: with the degeneracy test, the axis (x) is
  // the prior's alone; without it the scan drags the estimate along the corridor.
  LocalMapOptions options;
  options.size = 20.0;
  RollingWindow window(options, Eigen::Vector2d::Zero(), false);
  const std::vector<internal::Segment> corridor = {{{-50.0, -0.975}, {50.0, -0.975}},
                                                   {{-50.0, 1.025}, {50.0, 1.025}}};
  for (double x = -2.0; x <= 2.0; x += 0.5) {
    window.InsertScan(Pose2(x, 0.0, 0.0),
                      ExtractScanPoints(SimulateScan(corridor, Pose2(x, 0.0, 0.0)), Pose2(), 30.0));
  }
  MatchingField field(0.3);
  field.Update(window);
  const ScanPoints scan =
      ExtractScanPoints(SimulateScan(corridor, Pose2(0.0, 0.1, 0.05)), Pose2(), 30.0);
  const double information = 1.0 / (0.09 * 0.09);
  const Eigen::Matrix3d prior = Eigen::Vector3d::Constant(information).asDiagonal();
  const Pose2 predicted(0.3, 0.0, 0.0);
  ScanMatcherOptions matcher_options = MatcherOptions("distance_field");
  const MatchResult result =
      ScanMatcher(matcher_options).Match(window, field, scan, predicted, prior);
  ASSERT_TRUE(result.ok);
  EXPECT_EQ(result.degeneracy.degenerate_directions, 1);
  EXPECT_GT(std::abs(result.degeneracy.weakest_direction.x()), 0.99);
  EXPECT_LT(result.degeneracy.weakest_points,
            matcher_options.degenerate_fraction * result.correspondences);
  EXPECT_NEAR(result.T_odom_base.x(), predicted.x(), 1e-3);
  EXPECT_NEAR(result.T_odom_base.y(), 0.1, 0.03);
  EXPECT_NEAR(result.T_odom_base.theta(), 0.05, DegToRad(0.5));
  // The covariance is the prior's along the axis.
  EXPECT_NEAR(result.covariance(0, 0), 1.0 / information, 0.1 / information);

  // The test off: the scan's few points along the axis claim more than the prior knows.
  matcher_options.degenerate_fraction = 0.0;
  const MatchResult free =
      ScanMatcher(matcher_options).Match(window, field, scan, predicted, prior);
  ASSERT_TRUE(free.ok);
  EXPECT_EQ(free.degeneracy.degenerate_directions, 0);
  EXPECT_LT(free.covariance(0, 0), 0.9 * result.covariance(0, 0));
}

// The same corridor seen by a noisy laser (3 cm at 1 degree): five beams span 7 cm of wall at
// 1 m, so the five-beam normals scatter by tens of degrees and pass the distance gradient along
// the walls into the scan's information: the axis no longer looks degenerate. Judged on the wall
// normals (fitted to as many beams as the measured noise needs) it is degenerate again, and the
// prior holds it.
TEST(ScanMatcher, NoisyCorridorAxisIsFoundOnTheWallNormals) {
  LocalMapOptions options;
  options.size = 20.0;
  const std::vector<internal::Segment> corridor = {{{-50.0, -0.975}, {50.0, -0.975}},
                                                   {{-50.0, 1.025}, {50.0, 1.025}}};
  NormalEstimation walls;
  walls.max_angle_sigma = 0.1;
  const double information = 1.0 / (0.09 * 0.09);
  const Eigen::Matrix3d prior = Eigen::Vector3d::Constant(information).asDiagonal();
  const Pose2 predicted(0.3, 0.0, 0.0);
  const auto match = [&](const NormalEstimation& normals) {
    RollingWindow window(options, Eigen::Vector2d::Zero(), false);
    unsigned seed = 1;
    for (double x = -2.0; x <= 2.0; x += 0.5) {
      window.InsertScan(
          Pose2(x, 0.0, 0.0),
          ExtractScanPoints(SimulateScan(corridor, Pose2(x, 0.0, 0.0), 181, 30.0, 0.03, seed++),
                            Pose2(), 30.0, normals));
    }
    MatchingField field(0.3);
    field.Update(window);
    const ScanPoints scan = ExtractScanPoints(
        SimulateScan(corridor, Pose2(0.0, 0.1, 0.05), 181, 30.0, 0.03, 99), Pose2(), 30.0, normals);
    EXPECT_EQ(scan.wall_normals.empty(), normals.max_angle_sigma == 0.0);
    return ScanMatcher(MatcherOptions("distance_field"))
        .Match(window, field, scan, predicted, prior);
  };
  const MatchResult five_beams = match(NormalEstimation{});
  ASSERT_TRUE(five_beams.ok);
  EXPECT_EQ(five_beams.degeneracy.degenerate_directions, 0);
  const MatchResult on_walls = match(walls);
  ASSERT_TRUE(on_walls.ok);
  EXPECT_EQ(on_walls.degeneracy.degenerate_directions, 1);
  EXPECT_GT(std::abs(on_walls.degeneracy.weakest_direction.x()), 0.99);
  EXPECT_LT(on_walls.degeneracy.weakest_points, 0.5 * five_beams.degeneracy.weakest_points);
  // Along the axis the scan moved the five-beam match by 8 mm, the wall-normal one by 2 mm.
  EXPECT_NEAR(on_walls.T_odom_base.x(), predicted.x(), 5e-3);
  EXPECT_LT(std::abs(on_walls.T_odom_base.x() - predicted.x()),
            0.5 * std::abs(five_beams.T_odom_base.x() - predicted.x()));
  EXPECT_NEAR(on_walls.T_odom_base.y(), 0.1, 0.03);
}

TEST(ScanMatcher, ARoomHasNoDegenerateDirection) {
  const ShiftedMap map{Pose2()};
  const Eigen::Matrix3d prior = Eigen::Vector3d::Constant(100.0).asDiagonal();
  for (const Pose2& truth : {Pose2(3.0, 1.5, 0.2), Pose2(7.0, 3.0, 2.0)}) {
    const ScanPoints scan = ExtractScanPoints(SimulateScan(TestWorld(), truth, 361), Pose2(), 30.0);
    const MatchResult result = ScanMatcher(MatcherOptions("distance_field"))
                                   .Match(map.window, map.field, scan, truth, prior);
    ASSERT_TRUE(result.ok);
    EXPECT_EQ(result.degeneracy.degenerate_directions, 0);
    EXPECT_GT(result.degeneracy.weakest_points, 10.0);
  }
}

// The window's storage rotates as it recentres: a window whose storage is rotated (it started
// elsewhere and recentred onto the same cells) must give bit-identical matches and searches. A
// power-of-two resolution keeps the two windows' origins exact.
TEST(ScanMatcher, StorageRotationDoesNotChangeTheMatch) {
  LocalMapOptions options = ShiftedMap::Options();
  options.resolution = 0.0625;
  const Eigen::Vector2d centre(6.0, 3.5);
  RollingWindow plain(options, centre, true);
  RollingWindow rotated(options, centre + Eigen::Vector2d(3.0, -2.0), true);
  ASSERT_TRUE((rotated.Recentre(centre) != 0).all());
  ASSERT_EQ(plain.Limits().Origin(), rotated.Limits().Origin());
  for (const Pose2& pose : MapPoses()) {
    const ScanPoints points = ExtractScanPoints(SimulateScan(TestWorld(), pose), Pose2(), 30.0);
    plain.InsertScan(pose, points);
    rotated.InsertScan(pose, points);
  }
  MatchingField plain_field(0.3);
  MatchingField rotated_field(0.3);
  plain_field.Update(plain);
  rotated_field.Update(rotated);
  ASSERT_FALSE(plain_field.Layout() == rotated_field.Layout());
  for (const std::string residual : {"distance_field", "point_to_line"}) {
    const ScanMatcher matcher(MatcherOptions(residual));
    for (const Pose2& truth :
         {Pose2(3.0, 1.5, 0.2), Pose2(7.0, 3.0, 2.0), Pose2(12.0, 3.6, -0.1)}) {
      const ScanPoints scan =
          ExtractScanPoints(SimulateScan(TestWorld(), truth, 361), Pose2(), 30.0);
      const Pose2 prior = Pose2(0.2, -0.15, 0.1) * truth;  // far enough to need the search
      const MatchResult a = matcher.Match(plain, plain_field, scan, prior, Eigen::Matrix3d::Zero());
      const MatchResult b =
          matcher.Match(rotated, rotated_field, scan, prior, Eigen::Matrix3d::Zero());
      EXPECT_EQ(a.T_odom_base.ToVector(), b.T_odom_base.ToVector()) << residual;
      EXPECT_EQ(a.score, b.score);
      EXPECT_EQ(a.correspondences, b.correspondences);
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_EQ(a.searched, b.searched);
      const SearchResult sa = CorrelativeSearch(plain_field, scan, prior, MatcherOptions(residual));
      const SearchResult sb =
          CorrelativeSearch(rotated_field, scan, prior, MatcherOptions(residual));
      EXPECT_EQ(sa.T_odom_base.ToVector(), sb.T_odom_base.ToVector());
      EXPECT_EQ(sa.score, sb.score);
    }
  }
}

}  // namespace
}  // namespace gridslam::scan_matching
