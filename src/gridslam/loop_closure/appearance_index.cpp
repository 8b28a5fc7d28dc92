#include "gridslam/loop_closure/appearance_index.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/flann.hpp>

namespace gridslam::loop_closure {

struct AppearanceIndex::Block {
  cv::Mat descriptors;     ///< All rows of the block's key maps.
  std::vector<int> owner;  ///< Key-map id of each row.
  int key_maps = 0;
  bool sealed = false;                     ///< Full: no more key maps go into it.
  std::unique_ptr<cv::flann::Index> tree;  ///< Built when a block of float descriptors is full.
};

AppearanceIndex::AppearanceIndex(int block_size, double ratio,
                                 std::shared_ptr<cv::RNG> random_state)
    : block_size_(std::max(1, block_size)),
      ratio_(ratio),
      random_state_(random_state != nullptr ? std::move(random_state) : NewRandomState()) {}

std::shared_ptr<cv::RNG> AppearanceIndex::NewRandomState() { return std::make_shared<cv::RNG>(); }

AppearanceIndex::~AppearanceIndex() = default;

namespace {

bool Indexable(const cv::Mat& descriptors) {
  return !descriptors.empty() && (descriptors.type() == CV_32F || descriptors.type() == CV_8U);
}

}  // namespace

void AppearanceIndex::Add(int node, const cv::Mat& descriptors) {
  if (!Indexable(descriptors) || (type_ >= 0 && descriptors.type() != type_)) {
    return;
  }
  type_ = descriptors.type();
  if (blocks_.empty() || blocks_.back()->sealed) {
    blocks_.push_back(std::make_unique<Block>());
  }
  Block& tail = *blocks_.back();
  tail.descriptors.push_back(descriptors);
  tail.owner.insert(tail.owner.end(), static_cast<std::size_t>(descriptors.rows), node);
  ++tail.key_maps;
  if (tail.key_maps >= block_size_) {
    SealTail();
  }
}

void AppearanceIndex::SealTail() {
  Block& tail = *blocks_.back();
  tail.sealed = true;
  if (type_ != CV_32F) {
    return;  // binary descriptors: brute-force Hamming distances
  }
  // FLANN draws its trees from this thread's cv::theRNG(): lend it our state.
  cv::RNG& rng = cv::theRNG();
  const cv::RNG saved = rng;
  rng = *random_state_;
  tail.tree = std::make_unique<cv::flann::Index>(tail.descriptors, cv::flann::KDTreeIndexParams(4),
                                                 cvflann::FLANN_DIST_L2);
  *random_state_ = rng;
  rng = saved;
}

std::vector<AppearanceVote> AppearanceIndex::Query(const cv::Mat& descriptors, int max_results,
                                                   int min_votes,
                                                   const std::function<bool(int)>& allowed) const {
  std::vector<AppearanceVote> result;
  if (!Indexable(descriptors) || descriptors.type() != type_ || max_results <= 0) {
    return result;
  }
  // The k nearest stored descriptors of every query row over all blocks, among allowed key
  // maps. Each distinct owner among them gets one vote: consecutive key maps share most of their
  // content, so a place's descriptor has near-duplicates in several neighbouring key maps, and a
  // ratio test against the runner-up would reject exactly the true matches.
  const int n = descriptors.rows;
  constexpr int kNeighbours = 5;
  std::vector<std::vector<std::pair<float, int>>> nearest(static_cast<std::size_t>(n));
  for (const auto& block : blocks_) {
    const int kk = std::min(kNeighbours, block->descriptors.rows);
    cv::Mat indices;
    cv::Mat dists;
    if (block->tree != nullptr) {
      block->tree->knnSearch(descriptors, indices, dists, kk, cv::flann::SearchParams(32));
    } else if (type_ == CV_8U) {
      // Hamming distances, squared so that the ratio below compares distances as for L2.
      cv::Mat hamming;
      cv::batchDistance(descriptors, block->descriptors, hamming, CV_32S, indices, cv::NORM_HAMMING,
                        kk);
      hamming.convertTo(dists, CV_32F);
      dists = dists.mul(dists);
    } else {
      cv::batchDistance(descriptors, block->descriptors, dists, CV_32F, indices, cv::NORM_L2SQR,
                        kk);
    }
    for (int q = 0; q < n; ++q) {
      auto& list = nearest[static_cast<std::size_t>(q)];
      for (int c = 0; c < kk; ++c) {
        const int row = indices.at<int>(q, c);
        if (row < 0) {
          continue;
        }
        const int owner = block->owner[static_cast<std::size_t>(row)];
        if (allowed(owner)) {
          list.emplace_back(dists.at<float>(q, c), owner);
        }
      }
    }
  }
  std::map<int, int> votes;
  const auto ratio_sq = static_cast<float>(ratio_ * ratio_);
  for (auto& list : nearest) {
    if (list.empty()) {
      continue;
    }
    std::sort(list.begin(), list.end());
    if (list.size() > static_cast<std::size_t>(kNeighbours)) {
      list.resize(static_cast<std::size_t>(kNeighbours));
    }
    // Distinctiveness: the neighbours that vote must be clearly nearer than the k-th one (the
    // k-th is usually another place; only near-duplicates of one place pass).
    const float limit = ratio_sq * list.back().first;
    std::vector<int> voted;
    for (std::size_t c = 0; c < list.size() && c < static_cast<std::size_t>(kNeighbours); ++c) {
      if (list[c].first >= limit) {
        break;
      }
      if (std::find(voted.begin(), voted.end(), list[c].second) == voted.end()) {
        voted.push_back(list[c].second);
        ++votes[list[c].second];
      }
    }
  }
  for (const auto& [node, count] : votes) {
    if (count >= min_votes) {
      result.push_back({node, count});
    }
  }
  std::sort(result.begin(), result.end(), [](const AppearanceVote& a, const AppearanceVote& b) {
    return a.votes != b.votes ? a.votes > b.votes : a.node < b.node;
  });
  if (static_cast<int>(result.size()) > max_results) {
    result.resize(static_cast<std::size_t>(max_results));
  }
  return result;
}

}  // namespace gridslam::loop_closure
