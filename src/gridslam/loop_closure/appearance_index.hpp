// Global appearance search (docs/design.md §1.6, §1.9): which earlier key maps look like a new one,
// with no pose prior. Every key map's descriptors go into an index; each query descriptor votes
// once for every distinct key map among its k nearest stored descriptors that are clearly nearer
// than the k-th (distance below ratio times the k-th's: near-duplicates of one place, seen in
// several overlapping key maps), and the most-voted key maps are returned for alignment and
// verification. Float
// descriptors are indexed in blocks of key maps with randomized k-d trees (FLANN, as the authors'
// matcher); the newest, not yet full block is searched by brute force. Binary descriptors (ORB,
// AKAZE: CV_8U rows) are searched by brute force with Hamming distances. This is what lets robots
// with unknown relative starts find each other, and a lost robot relocalize.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

namespace gridslam::loop_closure {

struct AppearanceVote {
  int node = 0;   ///< Key-map id given to Add().
  int votes = 0;  ///< Query descriptors whose nearest neighbour belongs to it.
};

class AppearanceIndex {
 public:
  static constexpr int kDefaultBlockSize = 64;
  static constexpr double kDefaultRatio = 0.8;
  /// `block_size`: key maps per k-d tree block; `ratio`: a neighbour votes when its distance is
  /// below `ratio` times that of the k-th (5th) nearest. `random_state`: the state FLANN's
  /// randomized trees are drawn from, continued from block to block (indices given the same one
  /// share it, in the order their blocks are built); null: the index's own. The trees then do not
  /// depend on the thread that builds them or on what else used OpenCV's random numbers.
  explicit AppearanceIndex(int block_size = kDefaultBlockSize, double ratio = kDefaultRatio,
                           std::shared_ptr<cv::RNG> random_state = nullptr);
  /// A random state as a fresh thread's cv::theRNG() starts.
  static std::shared_ptr<cv::RNG> NewRandomState();
  ~AppearanceIndex();
  AppearanceIndex(const AppearanceIndex&) = delete;
  AppearanceIndex& operator=(const AppearanceIndex&) = delete;

  /// Stores the descriptors of key map `node`: CV_32F (L2) or CV_8U (binary, Hamming) rows, all
  /// of the type first stored; other types are ignored.
  void Add(int node, const cv::Mat& descriptors);
  /// The `max_results` key maps with the most votes (at least `min_votes`) among those for which
  /// `allowed(node)` holds, best first.
  [[nodiscard]] std::vector<AppearanceVote> Query(const cv::Mat& descriptors, int max_results,
                                                  int min_votes,
                                                  const std::function<bool(int)>& allowed) const;

 private:
  struct Block;
  void SealTail();
  int block_size_;
  double ratio_;
  int type_ = -1;  ///< OpenCV type of the stored descriptors, -1 before the first.
  std::shared_ptr<cv::RNG> random_state_;
  std::vector<std::unique_ptr<Block>> blocks_;
};

}  // namespace gridslam::loop_closure
