// The matching field on the window's toroidal storage: fields that follow windows whose storage
// is rotated differently, fed the same scans and recentrings, must hold the same values in every
// logical cell (squared distance, distance, the logical cell of the nearest obstacle) and
// interpolate the same distances and gradients anywhere, the storage seam included; and their
// distances must equal the exact transform of the row-major reference window's obstacles.
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/grid/internal/lattice_world.hpp"
#include "gridslam/grid/internal/row_major_window.hpp"
#include "gridslam/scan_matching/matching_field.hpp"

namespace gridslam::scan_matching {
namespace {

using gridslam::internal::LatticeScan;
using gridslam::internal::RowMajorWindow;

struct Follower {
  RollingWindow window;
  MatchingField field;
};

// Every logical cell of the field, as bits: squared distance, distance, nearest logical cell
// (row-major logical index, -1 if none).
struct FieldCells {
  std::vector<std::uint32_t> squared;
  std::vector<std::uint32_t> distance;
  std::vector<std::int32_t> nearest;
};

FieldCells CellsOf(const Follower& f) {
  FieldCells cells;
  const MapLimits& limits = f.window.Limits();
  const int w = limits.Width();
  for (int j = 0; j < limits.Height(); ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t index = f.field.Layout().Index(i, j);
      cells.squared.push_back(std::bit_cast<std::uint32_t>(f.field.SquaredDistanceCells(index)));
      cells.distance.push_back(std::bit_cast<std::uint32_t>(f.field.Distance(index)));
      const std::int32_t label = f.field.Nearest(index);
      if (label < 0) {
        cells.nearest.push_back(-1);
      } else {
        const Eigen::Array2i c = f.window.Layout().Cell(static_cast<std::size_t>(label));
        cells.nearest.push_back(c.y() * w + c.x());
      }
    }
  }
  return cells;
}

template <typename T>
void ExpectSameCells(const std::vector<T>& a, const std::vector<T>& b, int width,
                     const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k], b[k]) << what << " differs at cell (" << k % width << ", " << k / width << ")";
  }
}

// Points where each field's bilinear lookup straddles its storage seam (the last stored column or
// row and the first), and random points all over the window and a little beyond.
std::vector<Eigen::Vector2d> ProbePoints(const std::vector<const Follower*>& followers,
                                         std::mt19937& rng) {
  std::vector<Eigen::Vector2d> points;
  const MapLimits& limits = followers.front()->window.Limits();
  const int w = limits.Width();
  const int h = limits.Height();
  const double res = limits.Resolution();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const Follower* f : followers) {
    // Logical column i is stored at column (i + offset) mod w: the seam lies between logical
    // columns w - offset - 1 and w - offset.
    const int seam_i = w - f->field.Layout().OffsetX() - 1;
    const int seam_j = h - f->field.Layout().OffsetY() - 1;
    for (int k = 0; k < 40; ++k) {
      const double along = unit(rng) * (h - 1);
      points.push_back(limits.Origin() + res * Eigen::Vector2d(seam_i + 0.5 + unit(rng), along));
      const double across = unit(rng) * (w - 1);
      points.push_back(limits.Origin() + res * Eigen::Vector2d(across, seam_j + 0.5 + unit(rng)));
    }
  }
  for (int k = 0; k < 400; ++k) {
    points.push_back(limits.Origin() + res * Eigen::Vector2d((1.04 * unit(rng) - 0.02) * w,
                                                             (1.04 * unit(rng) - 0.02) * h));
  }
  return points;
}

TEST(MatchingFieldEquivalence, RotatedStorageGivesTheSameFieldAsTheRowMajorTransform) {
  LocalMapOptions options;
  options.resolution = 0.0625;  // exact origins along different sequences of shifts
  options.size = 8.0;
  options.shift_distance = 0.2;
  options.max_range = 5.0;
  options.clear_no_returns = true;
  options.no_return_clearing_range = 3.0;
  const double max_distance = 0.3;
  const Eigen::Vector2d centre(-0.75, 2.125);
  // Storage offsets (total shift since construction, modulo the size) differ between the three.
  Follower plain{RollingWindow(options, centre), MatchingField(max_distance)};
  Follower moved{RollingWindow(options, centre + Eigen::Vector2d(2.5, -1.875)),
                 MatchingField(max_distance)};
  ASSERT_TRUE((moved.window.Recentre(centre) != 0).all());
  Follower detour{RollingWindow(options, centre + Eigen::Vector2d(-3.25, -2.75)),
                  MatchingField(max_distance)};
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(20.0, -15.0), centre}) {  // far and back
    ASSERT_TRUE((detour.window.Recentre(p) != 0).all());
  }
  const std::vector<Follower*> followers{&plain, &moved, &detour};
  ASSERT_FALSE(plain.window.Layout() == moved.window.Layout());
  ASSERT_FALSE(plain.window.Layout() == detour.window.Layout());
  ASSERT_FALSE(moved.window.Layout() == detour.window.Layout());
  for (Follower* f : followers) {
    ASSERT_EQ(f->window.Limits().Origin(), plain.window.Limits().Origin());
    f->window.ClearChanges();
  }
  RowMajorWindow reference(options, centre);
  const int w = plain.window.Limits().Width();
  const int h = plain.window.Limits().Height();
  const auto max_cells = static_cast<float>(max_distance / options.resolution);
  distance_transform::SquaredDistanceField exact;

  std::mt19937 rng(41);
  std::mt19937 probe_rng(43);
  std::uniform_real_distribution<double> step(-0.15, 0.3);
  Pose2 pose(centre.x(), centre.y(), 0.7);
  int updates = 0;
  int shifted_updates = 0;
  int piled_up_shifts = 0;  // updates that took two recentrings at once
  int shifts_since_update = 0;
  // Brings every field up to date with its window and checks them all, in logical cells.
  auto update_and_check = [&](const std::string& at) {
    shifted_updates += (plain.window.PendingShift() != 0).any() ? 1 : 0;
    piled_up_shifts += shifts_since_update > 1 ? 1 : 0;
    shifts_since_update = 0;
    reference.ClearChanges();
    for (Follower* f : followers) {
      f->field.Update(f->window);
      f->window.ClearChanges();
    }
    ++updates;
    const FieldCells expected = CellsOf(plain);
    for (const Follower* f : {&moved, &detour}) {
      const FieldCells cells = CellsOf(*f);
      const std::string who = at + (f == &moved ? ", moved" : ", detour");
      ExpectSameCells(cells.squared, expected.squared, w, who + ": squared distance");
      ExpectSameCells(cells.distance, expected.distance, w, who + ": distance");
      ExpectSameCells(cells.nearest, expected.nearest, w, who + ": nearest obstacle");
    }
    // The exact transform of the row-major window's obstacles, computed from scratch.
    distance_transform::SquaredEuclideanDistanceTransform(reference.Obstacles().data(), w, h, exact,
                                                          true, max_cells);
    std::vector<std::uint32_t> exact_squared;
    for (const float sq : exact.squared) {
      exact_squared.push_back(std::bit_cast<std::uint32_t>(sq));
    }
    ExpectSameCells(expected.squared, exact_squared, w, at + ": squared distance vs row-major");
    for (std::size_t c = 0; c < expected.nearest.size(); ++c) {
      const std::int32_t n = expected.nearest[c];
      if (n < 0) {
        continue;
      }
      ASSERT_EQ(reference.Obstacles().data()[n], 1) << at << ": nearest is not an obstacle";
      const int di = static_cast<int>(c) % w - n % w;
      const int dj = static_cast<int>(c) / w - n / w;
      ASSERT_EQ(static_cast<float>(di * di + dj * dj), exact.squared[c]) << at;
    }
    const std::vector<const Follower*> probes{&plain, &moved, &detour};
    for (const Eigen::Vector2d& p : ProbePoints(probes, probe_rng)) {
      Eigen::Vector2d g0;
      const double d0 = plain.field.Interpolate(p, &g0);
      for (const Follower* f : {&moved, &detour}) {
        Eigen::Vector2d g;
        const double d = f->field.Interpolate(p, &g);
        ASSERT_EQ(std::bit_cast<std::uint64_t>(d), std::bit_cast<std::uint64_t>(d0))
            << at << " at " << p.transpose();
        ASSERT_EQ(std::bit_cast<std::uint64_t>(g.x()), std::bit_cast<std::uint64_t>(g0.x()));
        ASSERT_EQ(std::bit_cast<std::uint64_t>(g.y()), std::bit_cast<std::uint64_t>(g0.y()));
      }
    }
  };
  bool pending = false;  // scans the fields have not taken yet
  for (int k = 0; k < 160; ++k) {
    // Drive around the whole block and back, so the seams cross the window both ways.
    const double heading = 0.5 * std::numbers::pi * (k / 40) + 0.3;
    pose = Pose2(pose.translation() +
                     step(rng) * Eigen::Vector2d(std::cos(heading), std::sin(heading)) +
                     Eigen::Vector2d(0.02 * step(rng), 0.02 * step(rng)),
                 pose.theta() + step(rng));
    const std::string at = "step " + std::to_string(k);
    // A field follows a pending shift that went one way along each axis; recentrings that go
    // back and forth between two updates are not handled (they leave stale cells, on row-major
    // storage as on the ring: DISABLED_ test below), so the fields take the changes first then.
    RowMajorWindow probe = reference;
    const Eigen::Array2i next_shift = probe.Recentre(pose.translation());
    if (pending && ((next_shift * plain.window.PendingShift()) < 0).any()) {
      update_and_check(at + " (before a reversing shift)");
      if (HasFatalFailure()) {
        return;
      }
    }
    reference.Recentre(pose.translation());
    for (Follower* f : followers) {
      f->window.Recentre(pose.translation());
    }
    shifts_since_update += (next_shift != 0).any() ? 1 : 0;
    const ScanPoints scan = LatticeScan(pose, rng, 0.05);
    reference.InsertScan(pose, scan);
    for (Follower* f : followers) {
      f->window.InsertScan(pose, scan);
    }
    pending = true;
    if (k % 3 == 2) {  // let changes and shifts pile up over two scans now and then
      continue;
    }
    update_and_check(at);
    pending = false;
    if (HasFatalFailure()) {
      return;
    }
  }
  EXPECT_GT(piled_up_shifts, 3);
  EXPECT_GT(shifted_updates, 30);
  EXPECT_GT(plain.window.NumObstacles(), 200);
  for (const Follower* f : followers) {
    // Only the first update rebuilds: every later one ran the incremental shift and change paths.
    EXPECT_EQ(f->field.NumRebuilds(), 1);
    EXPECT_GT(f->field.NumTileUpdates(), updates);
  }
}

// Recentrings that go back and forth along an axis between two updates clear cells the net
// shift does not cover: here a wall 0.12 m inside the right edge leaves with a shift of -4 cells
// and its cells come back, unknown, with a shift of +5. Following the net shift alone, the field
// kept seeing the wall (141 stale cells); the window reports the reversal and the field rebuilds.
TEST(MatchingFieldEquivalence, ShiftsBackAndForthBetweenUpdatesLeaveNoStaleCells) {
  LocalMapOptions options;
  options.resolution = 0.0625;
  options.size = 8.0;
  options.shift_distance = 0.2;
  options.max_range = 5.0;
  RollingWindow window(options, Eigen::Vector2d(0.7, 0.1));
  LaserScan scan;  // a wall at x = 4.613 m, 0.14 m inside the window's right edge (4.75 m)
  scan.angle_min = -0.1;
  scan.angle_increment = 0.01;
  scan.range_min = 0.05;
  scan.range_max = 20.0;
  for (int k = 0; k <= 20; ++k) {
    scan.ranges.push_back(
        static_cast<float>(3.913 / std::cos(scan.Angle(static_cast<std::size_t>(k)))));
  }
  window.InsertScan(Pose2(0.7, 0.1, 0.0), ExtractScanPoints(scan, Pose2(), 30.0));
  ASSERT_GT(window.NumObstacles(), 10);
  MatchingField field(0.3);
  field.Update(window);
  window.ClearChanges();
  ASSERT_EQ(window.Recentre({0.7 - 0.25, 0.1}).x(), -4);
  ASSERT_EQ(window.Recentre({0.7 + 0.0625, 0.1}).x(), 5);
  field.Update(window);
  MatchingField full(0.3);
  full.Rebuild(window);
  long stale = 0;
  for (long k = 0; k < window.Limits().NumCells(); ++k) {
    const auto index = static_cast<std::size_t>(k);
    stale += field.SquaredDistanceCells(index) != full.SquaredDistanceCells(index) ? 1 : 0;
  }
  EXPECT_EQ(stale, 0);
}

}  // namespace
}  // namespace gridslam::scan_matching
