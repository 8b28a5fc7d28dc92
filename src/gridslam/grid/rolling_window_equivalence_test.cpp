// The rolling window on toroidal storage (RingGrid) against the row-major window it replaced
// (internal::RowMajorWindow: every layer a Grid2D moved with Grid2D::Shift on recentring): fed the
// same scans and recentrings, both must hold the same logical cells bit for bit, whatever the
// ring's storage offsets, including shifts that carry the storage seam across the view in every
// direction and jumps farther than the window.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gridslam/grid/internal/lattice_world.hpp"
#include "gridslam/grid/internal/row_major_window.hpp"
#include "gridslam/grid/rolling_window.hpp"

namespace gridslam {
namespace {

using internal::LatticeScan;
using internal::RowMajorWindow;

// A small window (4 m) that recentres often, clears to max_range with the far returns and clears
// along no-return beams, so every path of InsertScan and Recentre runs.
LocalMapOptions TestOptions(double resolution) {
  LocalMapOptions options;
  options.resolution = resolution;
  options.size = 4.0;
  options.shift_distance = 0.2;
  options.max_range = 5.0;
  options.clear_no_returns = true;
  options.no_return_clearing_range = 3.0;
  return options;
}

// Everything a window holds, in logical cells (row-major over Limits()), as bits.
struct LogicalState {
  Eigen::Vector2d origin;
  long num_obstacles = 0;
  Eigen::Array2i pending_shift;
  bool overflow = false;
  std::vector<std::uint32_t> log_odds;
  std::vector<std::uint8_t> obstacles;
  std::vector<std::array<std::uint32_t, 5>> surfaces;
  std::vector<std::array<std::uint64_t, 2>> mean_points;
  std::vector<std::int32_t> changed;  ///< Row-major logical indices, in the order listed.
  std::vector<std::uint32_t> snapshot;
  Eigen::Vector2d snapshot_origin;
};

std::array<std::uint32_t, 5> Bits(const CellSurface& s) {
  return {std::bit_cast<std::uint32_t>(s.mean_x), std::bit_cast<std::uint32_t>(s.mean_y),
          std::bit_cast<std::uint32_t>(s.normal_x), std::bit_cast<std::uint32_t>(s.normal_y),
          s.hits};
}

std::array<std::uint64_t, 2> Bits(const Eigen::Vector2d& p) {
  return {std::bit_cast<std::uint64_t>(p.x()), std::bit_cast<std::uint64_t>(p.y())};
}

LogicalState StateOf(const RollingWindow& window) {
  LogicalState s;
  const MapLimits& limits = window.Limits();
  const int w = limits.Width();
  s.origin = limits.Origin();
  s.num_obstacles = window.NumObstacles();
  s.pending_shift = window.PendingShift();
  s.overflow = window.ChangesOverflow();
  for (int j = 0; j < limits.Height(); ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t index = window.Layout().Index(i, j);
      s.log_odds.push_back(std::bit_cast<std::uint32_t>(window.LogOdds()(i, j)));
      s.obstacles.push_back(window.Obstacles()(i, j));
      s.surfaces.push_back(Bits(window.Surface(index)));
      s.mean_points.push_back(Bits(window.MeanPoint(static_cast<std::int32_t>(index))));
    }
  }
  for (const std::int32_t index : window.ChangedCells()) {
    const Eigen::Array2i c = window.Layout().Cell(static_cast<std::size_t>(index));
    s.changed.push_back(c.y() * w + c.x());
  }
  const Grid2D<float> snapshot = window.SnapshotInCentreFrame(41);
  s.snapshot_origin = snapshot.Limits().Origin();
  for (const float l : snapshot.Cells()) {
    s.snapshot.push_back(std::bit_cast<std::uint32_t>(l));
  }
  return s;
}

LogicalState StateOf(const RowMajorWindow& window) {
  LogicalState s;
  const MapLimits& limits = window.Limits();
  const int w = limits.Width();
  const int h = limits.Height();
  s.origin = limits.Origin();
  s.num_obstacles = window.NumObstacles();
  s.pending_shift = window.PendingShift();
  s.overflow = window.ChangesOverflow();
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      s.log_odds.push_back(std::bit_cast<std::uint32_t>(window.LogOdds()(i, j)));
      s.obstacles.push_back(window.Obstacles()(i, j));
      s.surfaces.push_back(Bits(window.Surfaces()(i, j)));
      s.mean_points.push_back(Bits(window.MeanPoint(i, j)));
    }
  }
  s.changed = window.ChangedCells();
  // The central 41 x 41 cells, in the frame centred on the centre cell (SnapshotInCentreFrame).
  const int n = 41;
  const int i0 = w / 2 - n / 2;
  const int j0 = h / 2 - n / 2;
  const Eigen::Vector2d centre = limits.CellCenter(Eigen::Array2i(w / 2, h / 2));
  s.snapshot_origin = limits.Origin() + Eigen::Vector2d(i0, j0) * limits.Resolution() - centre;
  for (int j = j0; j < j0 + n; ++j) {
    for (int i = i0; i < i0 + n; ++i) {
      s.snapshot.push_back(std::bit_cast<std::uint32_t>(window.LogOdds()(i, j)));
    }
  }
  return s;
}

// The first difference, with the logical cell it lies in.
template <typename T>
void ExpectSameCells(const std::vector<T>& a, const std::vector<T>& b, int width,
                     const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_TRUE(a[k] == b[k]) << what << " differs at cell (" << k % width << ", " << k / width
                              << ")";
  }
}

void ExpectSameState(const LogicalState& a, const LogicalState& b, int width,
                     const std::string& what) {
  ASSERT_EQ(Bits(a.origin), Bits(b.origin)) << what << ": origin";
  ASSERT_EQ(a.num_obstacles, b.num_obstacles) << what << ": obstacle count";
  ASSERT_TRUE((a.pending_shift == b.pending_shift).all()) << what << ": pending shift";
  ASSERT_EQ(a.overflow, b.overflow) << what;
  ExpectSameCells(a.log_odds, b.log_odds, width, what + ": log-odds");
  ExpectSameCells(a.obstacles, b.obstacles, width, what + ": obstacles");
  ExpectSameCells(a.surfaces, b.surfaces, width, what + ": surfaces");
  ExpectSameCells(a.mean_points, b.mean_points, width, what + ": mean points");
  ASSERT_EQ(a.changed, b.changed) << what << ": changed cells";
  ASSERT_EQ(Bits(a.snapshot_origin), Bits(b.snapshot_origin)) << what << ": snapshot origin";
  ExpectSameCells(a.snapshot, b.snapshot, 41, what + ": snapshot");
}

// Which ways the storage seam has moved through the view: a positive shift that makes an offset
// wrap from the end of the storage to its start, or a negative one the other way.
struct SeamCrossings {
  bool x_forward = false;
  bool x_backward = false;
  bool y_forward = false;
  bool y_backward = false;

  void Note(const RingLayout& before, const RingLayout& after, const Eigen::Array2i& shift) {
    x_forward |= shift.x() > 0 && after.OffsetX() < before.OffsetX();
    x_backward |= shift.x() < 0 && after.OffsetX() > before.OffsetX();
    y_forward |= shift.y() > 0 && after.OffsetY() < before.OffsetY();
    y_backward |= shift.y() < 0 && after.OffsetY() > before.OffsetY();
  }
  [[nodiscard]] bool All() const { return x_forward && x_backward && y_forward && y_backward; }
};

// Drives the window along legs in the eight compass directions, each a window and a half long
// (the storage offsets wrap around at least once per leg), then jumps: half a window along x,
// along y, diagonally, and farther than the window. After every step the ring window must equal
// the row-major reference in every logical cell.
TEST(RollingWindowEquivalence, EqualsTheRowMajorWindowThroughRecentringsInEveryDirection) {
  const LocalMapOptions options = TestOptions(0.05);
  const Eigen::Vector2d start(0.31, -0.77);
  RollingWindow ring(options, start);
  RowMajorWindow reference(options, start);
  const int w = ring.Limits().Width();
  ASSERT_EQ(w, reference.Limits().Width());
  std::mt19937 rng(23);
  std::normal_distribution<double> noise(0.0, 0.02);
  SeamCrossings seams;
  int steps = 0;
  int shifts = 0;
  Pose2 pose(start.x(), start.y(), 0.3);
  auto step_to = [&](const Pose2& next) {
    pose = next;
    const RingLayout before = ring.Layout();
    const Eigen::Array2i shift = ring.Recentre(pose.translation());
    ASSERT_TRUE((reference.Recentre(pose.translation()) == shift).all()) << "step " << steps;
    seams.Note(before, ring.Layout(), shift);
    shifts += (shift != 0).any() ? 1 : 0;
    const ScanPoints scan = LatticeScan(pose, rng);
    ring.InsertScan(pose, scan);
    reference.InsertScan(pose, scan);
    ExpectSameState(StateOf(ring), StateOf(reference), w, "step " + std::to_string(steps));
    // Changes pile up over several recentrings before a consumer takes them, sometimes.
    if (steps % 4 != 3) {
      ring.ClearChanges();
      reference.ClearChanges();
    }
    ++steps;
  };
  const double leg = 1.5 * options.size;
  const double step = 0.11;
  for (int d = 0; d < 8; ++d) {
    const double heading = d * std::numbers::pi / 4;
    const Eigen::Vector2d direction(std::cos(heading), std::sin(heading));
    for (double s = 0.0; s < leg; s += step) {
      const Eigen::Vector2d p =
          pose.translation() + step * direction + Eigen::Vector2d(noise(rng), noise(rng));
      step_to(Pose2(p.x(), p.y(), pose.theta() + 5.0 * noise(rng)));
      if (HasFatalFailure()) {
        return;
      }
    }
  }
  for (const Eigen::Vector2d& jump :
       {Eigen::Vector2d(0.55 * options.size, 0.0), Eigen::Vector2d(0.0, -0.6 * options.size),
        Eigen::Vector2d(-0.7 * options.size, 0.45 * options.size),
        Eigen::Vector2d(2.5 * options.size, -1.2 * options.size),
        Eigen::Vector2d(-0.9 * options.size, -0.95 * options.size)}) {
    const Eigen::Vector2d p = pose.translation() + jump;
    step_to(Pose2(p.x(), p.y(), pose.theta() - 0.4));
    if (HasFatalFailure()) {
      return;
    }
    for (int k = 0; k < 5; ++k) {  // settle after the jump
      const Eigen::Vector2d q = pose.translation() + Eigen::Vector2d(noise(rng), noise(rng));
      step_to(Pose2(q.x(), q.y(), pose.theta()));
      if (HasFatalFailure()) {
        return;
      }
    }
  }
  EXPECT_TRUE(seams.All()) << seams.x_forward << seams.x_backward << seams.y_forward
                           << seams.y_backward;
  EXPECT_GT(shifts, 100);
  EXPECT_GT(ring.NumObstacles(), 100);
}

// Three windows over the same cells whose storage is rotated differently (the storage offset is
// the window's total shift since it was built, modulo its size): one built there, one built
// elsewhere and recentred onto the same cells, and one built elsewhere again that went on a
// detour first (shifts along x and y, some farther than the window, with scans inserted) and
// jumped back from afar (so it forgot the detour). Fed the same scans and recentrings they must
// hold the same logical cells as each other and as the row-major reference. A power-of-two
// resolution keeps the origins exact along the different sequences of shifts.
TEST(RollingWindowEquivalence, WindowsWithDifferentlyRotatedStorageHoldTheSameCells) {
  const LocalMapOptions options = TestOptions(0.0625);
  const Eigen::Vector2d centre(1.5, 0.25);
  RollingWindow plain(options, centre);
  RollingWindow moved(options, centre + Eigen::Vector2d(1.25, -0.875));
  ASSERT_TRUE((moved.Recentre(centre) != 0).all());
  RollingWindow detour(options, centre + Eigen::Vector2d(-2.0, 1.5));
  std::mt19937 detour_rng(31);
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(4.0, 0.25), Eigen::Vector2d(4.0, 3.5), Eigen::Vector2d(-2.5, 3.5),
        Eigen::Vector2d(-2.5, -3.0), Eigen::Vector2d(12.0, -9.0), centre}) {
    ASSERT_TRUE((detour.Recentre(p) != 0).any());
    if (p != centre) {
      detour.InsertScan(Pose2(p.x(), p.y(), 0.4),
                        LatticeScan(Pose2(p.x(), p.y(), 0.4), detour_rng));
    }
  }
  ASSERT_EQ(detour.NumObstacles(), 0);
  RowMajorWindow reference(options, centre);
  const int w = plain.Limits().Width();
  ASSERT_EQ(Bits(moved.Limits().Origin()), Bits(plain.Limits().Origin()));
  ASSERT_EQ(Bits(detour.Limits().Origin()), Bits(plain.Limits().Origin()));
  ASSERT_FALSE(plain.Layout() == moved.Layout());
  ASSERT_FALSE(plain.Layout() == detour.Layout());
  ASSERT_FALSE(moved.Layout() == detour.Layout());
  for (RollingWindow* window : {&plain, &moved, &detour}) {
    window->ClearChanges();
  }
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> step(-0.2, 0.3);
  Pose2 pose(centre.x(), centre.y(), -0.2);
  for (int k = 0; k < 150; ++k) {
    pose = pose * Pose2(step(rng), 0.6 * step(rng), 0.8 * step(rng));
    const Eigen::Array2i shift = reference.Recentre(pose.translation());
    for (RollingWindow* window : {&plain, &moved, &detour}) {
      ASSERT_TRUE((window->Recentre(pose.translation()) == shift).all());
    }
    const ScanPoints scan = LatticeScan(pose, rng);
    reference.InsertScan(pose, scan);
    for (RollingWindow* window : {&plain, &moved, &detour}) {
      window->InsertScan(pose, scan);
    }
    const std::string at = "step " + std::to_string(k);
    const LogicalState expected = StateOf(plain);
    ExpectSameState(StateOf(moved), expected, w, at + ", moved vs plain");
    ExpectSameState(StateOf(detour), expected, w, at + ", detour vs plain");
    ExpectSameState(expected, StateOf(reference), w, at + ", plain vs row-major");
    if (HasFatalFailure()) {
      return;
    }
    if (k % 3 != 2) {
      reference.ClearChanges();
      for (RollingWindow* window : {&plain, &moved, &detour}) {
        window->ClearChanges();
      }
    }
  }
  EXPECT_GT(plain.NumObstacles(), 100);
}

}  // namespace
}  // namespace gridslam
