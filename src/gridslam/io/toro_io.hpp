// Reading and writing 2-D pose graphs in TORO's text format (docs/formats.md §3; TORO's
// TreePoseGraph2::load/save): `VERTEX2 id x y theta` (or `VERTEX`) and
// `EDGE2 id1 id2 dx dy dtheta I_ff I_fs I_ss I_rr I_fr I_sr` (or `EDGE`), with the information in
// TORO's order (f = forward x, s = sideward y, r = rotation) converted here, and only here, to
// the project's (x, y, theta) order. As GTSAM does, a zero on the information diagonal is taken
// as a sign of a file in another order and rejected. Some `.graph` files store a covariance in
// TORO order instead (GTSAM's NoiseFormatGRAPH): `covariance = true` inverts it on read.
#pragma once

#include <string>

#include "gridslam/common/result.hpp"
#include "gridslam/io/g2o_io.hpp"
#include "gridslam/pose_graph/pose_graph.hpp"

namespace gridslam::io {

struct ToroReadOptions {
  /// The six numbers are a covariance (TORO order), not an information matrix.
  bool covariance = false;
};

/// Parses TORO text; `file` names it in errors. EQUIV and unknown tags are skipped with one
/// warning per tag.
Result<pose_graph::PoseGraph> ParseToro(const std::string& text, const std::string& file,
                                        GraphReadStats* stats = nullptr,
                                        const ToroReadOptions& options = {});
/// Reads a TORO file (NotFound if it cannot be opened).
Result<pose_graph::PoseGraph> ReadToro(const std::string& path, GraphReadStats* stats = nullptr,
                                       const ToroReadOptions& options = {});
/// TORO text (VERTEX2 / EDGE2). TORO has no FIX: fixed flags are not written.
std::string FormatToro(const pose_graph::PoseGraph& graph);
/// Writes a TORO file atomically.
Status WriteToro(const std::string& path, const pose_graph::PoseGraph& graph);

}  // namespace gridslam::io
