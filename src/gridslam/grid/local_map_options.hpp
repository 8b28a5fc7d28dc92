// Options of the rolling-window local occupancy map (docs/design.md §1.3; docs/method.md §1.4).
// Probabilities are converted to log-odds once; every length is in metres.
#pragma once

#include "gridslam/common/options.hpp"

namespace gridslam {

struct LocalMapOptions {
  double resolution = 0.05;  ///< Cell side [m].
  /// Window side [m]; the cell count is made odd. Key maps are its central keymap.size metres
  /// (15 m); a larger window keeps the map the scan matcher sees longer and includes the far
  /// returns that hold the heading: drift on intel falls from 0.29 m (15 m) to 0.13 m (25 m) on
  /// all benchmark relations (docs/front_end.md).
  double size = 25.0;
  /// Side of the window the scan matcher sees [m]; 0 = 2 (max_range + shift_distance), so that
  /// every return inserted lies inside it wherever the robot is in its recentring margin. When it
  /// is larger than `size`, the front end keeps a second, larger window for matching only; the
  /// key maps stay the central part of the `size` window. In a hall or outdoors most returns lie
  /// beyond 12.5 m, and a corridor's end walls are what holds the estimate along it; a window
  /// that cuts them off leaves the matcher blind there (docs/front_end.md "Matching window").
  double matching_size = 0.0;
  double shift_distance = 1.0;        ///< Recentre when the robot is this far from the centre [m].
  double hit_probability = 0.7;       ///< Inverse sensor model at a beam's end cell.
  double miss_probability = 0.45;     ///< Inverse sensor model along the beam.
  double min_probability = 0.12;      ///< Clamp (keeps the map able to change back).
  double max_probability = 0.97;      ///< Clamp.
  double occupied_probability = 0.6;  ///< Cells above are obstacles (matching, distance transform).
  double max_range = 30.0;            ///< Returns beyond this are not inserted [m].
  bool clear_no_returns = false;      ///< Whether max-range/no-return beams clear free space.
  double no_return_clearing_range = 5.0;  ///< How far such beams clear, if enabled [m].
  int surface_memory = 20;  ///< Hits averaged into a cell's mean point and normal (moving window).
  /// Returns with no near neighbour that lie on the line through their neighbouring beams'
  /// returns get its normal (walls at grazing incidence, ExtractScanPoints).
  bool grazing_normals = true;
  /// The largest standard error of a wall normal's direction [rad] (0 = never): on a noisy laser
  /// the degeneracy test judges what the walls constrain on normals fitted to as many beams (up
  /// to 8 either side) as the scan's own measured noise needs for this. With noisy ranges and
  /// dense beams a five-beam normal is too short a stretch of wall to be pinned, and its error
  /// passes the distance gradient along a corridor's walls into the information, enough to hide
  /// the corridor's degeneracy. 0.1 rad = sqrt(degenerate_fraction / 2). On by default since
  /// round 13, when the noise that gates it (ScanPoints::surface_noise) came to be measured on
  /// compact windows only: measured on windows stretched across far walls it read a quiet laser
  /// as noisy and grew its normals where they smooth real structure (docs/front_end.md, "Round
  /// 13"; the whole matrix in docs/robustness.md).
  double normal_angle_sigma = 0.1;
  /// A laser is noisy, and gets the wall normals, when the median measured noise of its recent
  /// scans (ScanPoints::surface_noise) exceeds this multiple of the grid's quantization noise,
  /// resolution / sqrt(12) (0.0144 m at 0.05 m cells) [-]. A quieter laser's five-beam normals
  /// are limited by the cells, and on sparse or cropped scans of cluttered rooms the longer fits
  /// lose (docs/front_end.md, "Noisy lasers, gated").
  double normal_noise_ratio = 1.0;

  /// Number of cells along each side (odd, so the window has a centre cell).
  [[nodiscard]] int NumCells() const;
  /// The matching window's side [m]: matching_size, or its automatic value when 0.
  [[nodiscard]] double MatchingSize() const;
  /// These options with `size` = MatchingSize(): the matching window's.
  [[nodiscard]] LocalMapOptions MatchingWindow() const;

  template <class V>
  void Visit(V& v) {
    v("resolution", resolution, "Cell side [m]");
    v("size", size,
      "Side of the rolling window [m] (the cell count is made odd); key maps are its centre");
    v("matching_size", matching_size,
      "Side of the window scans are matched against [m]; 0 = 2 (max_range + shift_distance), "
      "every inserted return inside it; larger than size: a second window, for matching only");
    v("shift_distance", shift_distance,
      "The window is shifted (in whole cells) when the robot is this far from its centre [m]");
    v("hit_probability", hit_probability, "Occupancy probability of a beam's end cell");
    v("miss_probability", miss_probability, "Occupancy probability of cells a beam passed");
    v("min_probability", min_probability, "Lower clamp of a cell's probability");
    v("max_probability", max_probability, "Upper clamp of a cell's probability");
    v("occupied_probability", occupied_probability,
      "Cells above this probability are obstacles for matching and distance transforms");
    v("max_range", max_range, "Returns farther than this are not inserted [m]");
    v("clear_no_returns", clear_no_returns,
      "Whether no-return (max-range) beams clear free space (they never mark obstacles)");
    v("no_return_clearing_range", no_return_clearing_range,
      "How far a no-return beam clears when clear_no_returns is set [m]");
    v("surface_memory", surface_memory,
      "Number of recent hits averaged into a cell's mean hit point and surface normal");
    v("grazing_normals", grazing_normals,
      "Isolated returns on the line through their neighbours get its normal (grazing walls)");
    v("normal_angle_sigma", normal_angle_sigma,
      "Largest standard error of the wall normals the degeneracy test uses [rad]: they fit more "
      "beams where the scan's measured noise demands it (0 = the five-beam normals)");
    v("normal_noise_ratio", normal_noise_ratio,
      "The wall normals are used when the laser's measured noise exceeds this multiple of the "
      "grid's quantization noise, resolution / sqrt(12) [-]");
  }
  /// The measured laser noise above which the wall normals are used [m].
  [[nodiscard]] double WallNormalNoise() const;
  [[nodiscard]] Status Validate() const;
};

}  // namespace gridslam
