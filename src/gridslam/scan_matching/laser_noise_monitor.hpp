// How noisy is the laser? The front end decides from the scans it has seen whether the five-beam
// normals of a scan are good enough for the degeneracy test, or whether the wall normals
// (ScanPoints::wall_normals, fitted to more beams) must stand in for them. Each scan measures its
// own scatter about its walls (ScanPoints::surface_noise); this monitor keeps the median of the
// last `window` of them, so that one cluttered or sparse scan does not switch the normals on and
// off, and compares it with the grid's own quantization noise: a laser quieter than the cells it
// is drawn in leaves the five-beam normals limited by the grid, not by its noise.
#pragma once

#include <cstddef>
#include <vector>

namespace gridslam::scan_matching {

class LaserNoiseMonitor {
 public:
  /// `window` recent scans [-] (> 0).
  explicit LaserNoiseMonitor(int window = 101);

  /// Adds a scan's measured noise [m]; values <= 0 (no five-beam window) are ignored.
  void Add(double surface_noise);
  /// Median of the recent scans' noise [m]; 0 before `min_scans` have been added.
  [[nodiscard]] double Median() const { return median_; }
  /// Whether the median exceeds `threshold` [m] (false before `min_scans` scans).
  [[nodiscard]] bool Above(double threshold) const { return median_ > threshold; }

  static constexpr std::size_t kMinScans = 10;

 private:
  std::size_t window_;
  std::vector<double> recent_;  ///< Ring of the last window_ values.
  std::size_t next_ = 0;        ///< Where the next value goes once recent_ is full.
  double median_ = 0.0;
};

}  // namespace gridslam::scan_matching
