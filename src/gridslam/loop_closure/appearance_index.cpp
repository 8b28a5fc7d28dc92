#include "gridslam/loop_closure/appearance_index.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/core/hal/hal.hpp>
#include <opencv2/flann.hpp>

#include "gridslam/common/check.hpp"

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

// A stored row is dropped as soon as its partial sum over the first 16, 32, ... dimensions reaches
// the query's current kk-th distance: the whole sum is no smaller, so the row could not enter the
// list. The margin covers the rounding of the partial sum against the kernel's (relative 1e-4,
// against 64 float additions' 4e-6).
void NearestByPartialSums(const cv::Mat& queries, const cv::Mat& stored, int kk, cv::Mat* dists,
                          cv::Mat* indices) {
  constexpr int kChunk = 16;
  constexpr float kMargin = 1.0F - 1e-4F;
  GRIDSLAM_CHECK(queries.type() == CV_32F && stored.type() == CV_32F &&
                 queries.cols == stored.cols && kk >= 1 && kk <= stored.rows);
  const int dims = queries.cols;
  dists->create(queries.rows, kk, CV_32F);
  indices->create(queries.rows, kk, CV_32S);
  dists->setTo(std::numeric_limits<float>::max());
  indices->setTo(-1);
  for (int q = 0; q < queries.rows; ++q) {
    const float* a = queries.ptr<float>(q);
    float* dist = dists->ptr<float>(q);
    int* index = indices->ptr<int>(q);
    for (int j = 0; j < stored.rows; ++j) {
      const float* b = stored.ptr<float>(j);
      float partial = 0.0F;
      bool beyond = false;
      for (int begin = 0; begin < dims && !beyond; begin += kChunk) {
        const int end = std::min(dims, begin + kChunk);
        for (int i = begin; i < end; ++i) {
          const float v = a[i] - b[i];
          partial += v * v;
        }
        beyond = partial * kMargin >= dist[kk - 1];
      }
      if (beyond) {
        continue;
      }
      const float d = cv::hal::normL2Sqr_(a, b, dims);
      if (d < dist[kk - 1]) {  // cv::batchDistance's insertion: ties keep the earlier row
        int k = kk - 2;
        for (; k >= 0 && dist[k] > d; --k) {
          dist[k + 1] = dist[k];
          index[k + 1] = index[k];
        }
        dist[k + 1] = d;
        index[k + 1] = j;
      }
    }
  }
}

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
      NearestByPartialSums(descriptors, block->descriptors, kk, &dists, &indices);
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
