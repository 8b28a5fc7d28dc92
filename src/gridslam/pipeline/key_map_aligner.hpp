// Aligning two key maps of the graph (docs/design.md §1.5, §1.6): the mapper's parts ask an Aligner
// for the pose of key map k in key map i's frame, and never look at features or grids
// themselves, so tests can script the answers (a ScriptedAligner on a synthetic graph).
// FeatureAligner is the real one: SURF matching + RANSAC + verification, refined on the
// distance field; with a prediction, a failed feature alignment falls back to refining the
// prediction (seeded by a correlative search when the uncertainty allows a large error).
#pragma once

#include <optional>
#include <span>

#include "gridslam/loop_closure/loop_closure_options.hpp"
#include "gridslam/matching/align.hpp"
#include "gridslam/pipeline/key_map_graph.hpp"

namespace gridslam::pipeline {

/// A verified alignment.
struct Alignment {
  Pose2 T_i_k;
  /// Found by the correlative search around the prediction: never trusted alone (the arbiter
  /// treats it as outside the gate).
  bool from_search = false;
};

class Aligner {
 public:
  virtual ~Aligner() = default;
  /// The pose of key map k in i's frame, or nullopt when the two do not align (verified).
  /// `prior`: the predicted T_i_k, or null; `uncertainty_distance` between the two [m].
  virtual std::optional<Alignment> Align(int i, int k, const Pose2* prior,
                                         double uncertainty_distance) = 0;
};

/// What FeatureAligner counted.
struct AlignerCounters {
  long verified = 0;        ///< Alignments accepted by matching + verification.
  long prior_refined = 0;   ///< Found by refinement from the prediction.
  long prior_searches = 0;  ///< Correlative searches around the prediction.
};

class FeatureAligner : public Aligner {
 public:
  /// `graph` is borrowed (its key maps' descriptions are aligned).
  FeatureAligner(const KeyMapGraph& graph, const matching::AlignOptions& matching,
                 const loop_closure::LoopClosureOptions& loop_closure);
  std::optional<Alignment> Align(int i, int k, const Pose2* prior,
                                 double uncertainty_distance) override;
  [[nodiscard]] const AlignerCounters& counters() const { return counters_; }

 private:
  std::optional<Alignment> RefineFromPrior(int i, int k, const Pose2& T_i_k,
                                           const matching::VerificationInput& verification,
                                           double uncertainty_distance);
  [[nodiscard]] std::span<const Eigen::Vector2d> RefinementPoints(const KeyMapNode& b) const;

  const KeyMapGraph& graph_;
  matching::AlignOptions matching_;
  loop_closure::LoopClosureOptions options_;
  AlignerCounters counters_;
};

}  // namespace gridslam::pipeline
