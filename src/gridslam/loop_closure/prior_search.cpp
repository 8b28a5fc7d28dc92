#include "gridslam/loop_closure/prior_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "gridslam/common/check.hpp"
#include "gridslam/common/thread_scratch.hpp"

namespace gridslam::loop_closure {

Status PriorSearchOptions::Validate() const {
  GRIDSLAM_RETURN_IF_ERROR(Require(window_per_m >= 0.0 && wide_window_per_m >= 0.0 &&
                                       max_window_xy >= 0.0 && min_window_xy >= 0.0 &&
                                       window_theta >= 0.0 && window_theta_per_m >= 0.0 &&
                                       max_window_theta >= 0.0,
                                   "prior_search windows >= 0"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(linear_step > 0.0 && angular_step > 0.0, "prior_search steps > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(truncation > 0.0, "prior_search.truncation > 0"));
  GRIDSLAM_RETURN_IF_ERROR(Require(max_points >= 1, "prior_search.max_points >= 1"));
  GRIDSLAM_RETURN_IF_ERROR(
      Require(min_score >= 0.0 && min_score <= 1.0, "0 <= prior_search.min_score <= 1"));
  GRIDSLAM_RETURN_IF_ERROR(Require(distinct_distance > 0.0, "prior_search.distinct_distance > 0"));
  return Require(max_ambiguity > 0.0 && max_ambiguity <= 1.0,
                 "0 < prior_search.max_ambiguity <= 1");
}

namespace internal {

// On x86-64 with GCC a clone for AVX2 (eight lanes, a 32-bit multiply and min/max of its own)
// is chosen at load time; the integers are the same either way.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void BlockCells(std::span<const int> ci, std::span<const int> cj, int di, int dj, int reach,
                int width, int height, std::span<int> cells) {
  const auto zero = static_cast<unsigned>(width * height);
  const std::size_t n = ci.size();
  for (std::size_t k = 0; k < n; ++k) {
    const int i = ci[k] + di;
    const int j = cj[k] + dj;
    // `&`, not `&&`: no branch, so that the loop vectorizes.
    const bool hits = (i < width) & (j < height) & (i + reach > 0) & (j + reach > 0);
    // A hit lies below the grid's upper ends: clipping it needs only the lower ones. Unsigned, as
    // a miss's cell, which is not used, may wrap.
    const unsigned cell = static_cast<unsigned>(std::max(j, 0)) * static_cast<unsigned>(width) +
                          static_cast<unsigned>(std::max(i, 0));
    cells[k] = static_cast<int>(hits ? cell : zero);
  }
}

void MaxInto(std::span<float> out, std::span<const float> in) {
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    // As std::max(out, in), without the reference that keeps the loop from vectorizing.
    out[i] = out[i] < in[i] ? in[i] : out[i];
  }
}

void TruncatedScores(std::span<const float> distance, float inv_truncation,
                     std::span<float> score) {
  const std::size_t n = distance.size();
  for (std::size_t c = 0; c < n; ++c) {
    // max(0, 1 - d / truncation) on known cells, 0 on unknown ones, as one select (no branch:
    // the loop vectorizes).
    const float s = 1.0F - distance[c] * inv_truncation;
    score[c] = ((distance[c] >= 0.0F) & (s > 0.0F)) ? s : 0.0F;
  }
}

int FirstStepAtLeast(int start, int step, int bound) {
  if (start >= bound) {
    return 0;
  }
  // In 64 bits: `start` may be far below the grid (a point far off it).
  const long long steps = (static_cast<long long>(bound) - start + step - 1) / step;
  return static_cast<int>(std::min<long long>(steps, std::numeric_limits<int>::max()));
}

void MaxOf(std::span<float> out, std::span<const float> a, std::span<const float> b) {
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = a[i] < b[i] ? b[i] : a[i];
  }
}

void ShiftedMax(std::span<float> out, std::span<const float> in, int shift) {
  const std::size_t n = out.size();
  const std::size_t offset = std::min(n, static_cast<std::size_t>(shift));
  const std::size_t shifted = n - offset;  // the values with a partner `shift` further on
  MaxOf(out.first(shifted), in.first(shifted), in.subspan(offset, shifted));
  std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(shifted), offset,
              out.begin() + static_cast<std::ptrdiff_t>(shifted));
}

}  // namespace internal

namespace {

// The lattice of poses a search scores: translations of `step` cells within +-half steps of the
// prior's, and rotations of angular_step within the rotation window; b's points subsampled.
struct SearchLattice {
  int step = 1;
  int half = 0;
  int side = 1;
  int angles = 1;
  std::vector<Eigen::Vector2d> points;
};

SearchLattice MakeLattice(std::span<const Eigen::Vector2d> points_b, double resolution,
                          double window_xy, double window_theta,
                          const PriorSearchOptions& options) {
  SearchLattice lattice;
  lattice.step = std::max(1, static_cast<int>(std::lround(options.linear_step / resolution)));
  lattice.half = static_cast<int>(std::floor(window_xy / (lattice.step * resolution)));
  lattice.side = 2 * lattice.half + 1;
  lattice.angles = 2 * static_cast<int>(std::floor(window_theta / options.angular_step)) + 1;
  const std::size_t stride =
      std::max<std::size_t>(1, points_b.size() / static_cast<std::size_t>(options.max_points));
  for (std::size_t k = 0; k < points_b.size(); k += stride) {
    lattice.points.push_back(points_b[k]);
  }
  return lattice;
}

// Lattice translations a rival search leaves out, in lattice steps: none, the disc of `radius`
// around (u, v), or the strip of half-width `radius` around the line through (u, v) with unit
// normal (nu, nv). Every rotation of an excluded translation is excluded.
struct Exclusion {
  enum class Shape { kNone, kDisc, kStrip };
  Shape shape = Shape::kNone;
  int u = 0;
  int v = 0;
  double radius = 0.0;
  double nu = 0.0;
  double nv = 0.0;

  [[nodiscard]] bool Contains(int pu, int pv) const {
    switch (shape) {
      case Shape::kNone:
        return false;
      case Shape::kDisc:
        return std::hypot(pu - u, pv - v) <= radius;
      case Shape::kStrip:
        return std::abs(nu * (pu - u) + nv * (pv - v)) <= radius;
    }
    return false;
  }
};

// Levels of max pools that cover a lattice side: the smallest L with 2^L >= side.
int PoolLevels(int side) {
  int levels = 0;
  while ((1 << levels) < side) {
    ++levels;
  }
  return levels;
}

// Branch and bound over the lattice (Hess et al., ICRA 2016, on the truncated score of
// SearchAroundPrior): a node is a square block of 2^level x 2^level translations at one rotation;
// its bound sums, over b's points, the largest cell score in the square the block's translations
// move the point over (precomputed max pools), so a block whose bound does not beat the best
// score so far holds no better pose. Leaves are scored exactly as the exhaustive search scores
// them, in the same order of summation: the best score is the same number.
class BranchAndBound {
 public:
  /// The buffers of a search, kept per thread from search to search (thread_scratch.hpp): a
  /// search writes every value it reads.
  struct Buffers {
    std::vector<float> score;
    std::vector<float> rows;
    std::vector<float> base;
    std::vector<std::vector<float>> pools;
    std::vector<int> cell_i;
    std::vector<int> cell_j;
    std::vector<int> cells;  ///< The cells a batch of bounds reads (internal::BlockCells).
  };

  BranchAndBound(const Grid2D<float>& distance_a, const Pose2& prior, const SearchLattice& lattice,
                 const PriorSearchOptions& options)
      : lattice_(lattice),
        width_(distance_a.Limits().Width()),
        height_(distance_a.Limits().Height()),
        buffers_(ThreadScratch<Buffers, Buffers>()) {
    const MapLimits& limits = distance_a.Limits();
    const std::size_t cells = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    // Bounds index the grid, and its zero cell past the end, with ints.
    GRIDSLAM_CHECK(cells < static_cast<std::size_t>(std::numeric_limits<int>::max()))
        << "prior search: a grid of " << cells << " cells";
    const float* field = distance_a.data();
    const auto inv_truncation = static_cast<float>(1.0 / options.truncation);
    buffers_.score.resize(cells + 1);
    internal::TruncatedScores(std::span<const float>(field, cells), inv_truncation,
                              std::span<float>(buffers_.score.data(), cells));
    buffers_.score[cells] = 0.0F;
    levels_ = PoolLevels(lattice.side);
    BuildPools();
    const std::size_t n = lattice.points.size();
    buffers_.cell_i.resize(static_cast<std::size_t>(lattice.angles) * n);
    buffers_.cell_j.resize(buffers_.cell_i.size());
    buffers_.cells.resize(static_cast<std::size_t>(kBatch) * n);
    for (int a = 0; a < lattice.angles; ++a) {
      const double dtheta = (a - lattice.angles / 2) * options.angular_step;
      const PointTransform T(prior * Pose2(0.0, 0.0, dtheta));
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d c = limits.ToCellCoordinates(T(lattice.points[k]));
        // The cell of the lattice's first translation (offset -half steps on both axes).
        buffers_.cell_i[a * n + k] =
            static_cast<int>(std::floor(c.x())) - lattice.half * lattice.step;
        buffers_.cell_j[a * n + k] =
            static_cast<int>(std::floor(c.y())) - lattice.half * lattice.step;
      }
    }
  }

  struct Best {
    float score = 0.0F;
    int a = 0;
    int u = 0;
    int v = 0;
    bool found = false;
  };

  // The best pose scoring more than `threshold` whose translation `exclusion` does not contain.
  // `scored` counts the bounds and leaves evaluated.
  Best Search(float threshold, const Exclusion& exclusion, long* scored) {
    exclusion_ = exclusion;
    Best best;
    best.score = threshold;
    std::vector<Node> roots;
    for (int a = 0; a < lattice_.angles; ++a) {
      roots.push_back(Node{a, levels_, 0, 0, 0.0F});
    }
    for (std::size_t first = 0; first < roots.size(); first += kBatch) {
      Bounds(roots.data() + first,
             static_cast<int>(std::min<std::size_t>(kBatch, roots.size() - first)), scored);
    }
    Descend(roots.data(), roots.data() + roots.size(), &best, scored);
    return best;
  }

 private:
  struct Node {
    int a;
    int level;
    int u0;
    int v0;
    float bound;
  };

  // buffers_.pools[L - 1](i, j) = the largest score over cells [i, i + 2^L step) x [j, j + 2^L
  // step) (clipped to the grid). Every pool is a largest value over a set of cells, built from
  // rows and columns apart in passes of internal::MaxInto: the largest of a set of scores (all
  // >= +0, none NaN) is the same number whatever the order it is taken in.
  void BuildPools() {
    const int w = width_;
    const int h = height_;
    const auto row = [w](std::vector<float>& grid, int j) {
      return std::span<float>(
          grid.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(w),
          static_cast<std::size_t>(w));
    };
    const auto cells = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    // Base: the square of one step.
    std::vector<float>& rows = buffers_.rows;
    std::vector<float>& base = buffers_.base;
    rows.resize(cells);
    base.resize(cells);
    for (int j = 0; j < h; ++j) {
      const std::span<float> out = row(rows, j);
      const std::span<float> in = row(buffers_.score, j);
      internal::ShiftedMax(out, in, std::min(1, lattice_.step - 1));
      for (int d = 2; d < lattice_.step && d < w; ++d) {
        internal::MaxInto(out.first(static_cast<std::size_t>(w - d)),
                          in.subspan(static_cast<std::size_t>(d)));
      }
    }
    for (int j = 0; j < h; ++j) {
      const std::span<float> out = row(base, j);
      internal::MaxOf(out, row(rows, j),
                      row(rows, std::min(j + std::min(1, lattice_.step - 1), h - 1)));
      for (int d = 2; d < lattice_.step && j + d < h; ++d) {
        internal::MaxInto(out, row(rows, j + d));
      }
    }
    if (buffers_.pools.size() < static_cast<std::size_t>(levels_)) {
      buffers_.pools.resize(static_cast<std::size_t>(levels_));
    }
    // Level L from level L - 1: the larger of (i, j) and (i + shift, j) where that lies on the
    // grid (into `rows`), then the larger of that at (i, j) and at (i, j + shift) where that does.
    std::vector<float>* previous = &base;
    for (int level = 1; level <= levels_; ++level) {
      const int shift = (1 << (level - 1)) * lattice_.step;
      for (int j = 0; j < h; ++j) {
        internal::ShiftedMax(row(rows, j), row(*previous, j), shift);
      }
      std::vector<float>& pool = buffers_.pools[static_cast<std::size_t>(level - 1)];
      pool.resize(cells + 1);  // with the zero cell
      pool.back() = 0.0F;
      for (int j = 0; j < h; ++j) {
        internal::MaxOf(row(pool, j), row(rows, j), row(rows, j + shift < h ? j + shift : j));
      }
      previous = &pool;
    }
  }

  // Exact scores of leaves (level 0), or bounds of blocks, for up to kBatch nodes of one level.
  // A leaf sums the scores of the cells its points land on (reach 1: a point off the grid adds
  // nothing); a block sums, per point, the pool of the cells [i, i + 2^level step) it moves the
  // point over, read at the first cell clipped to the grid (the pool there covers the rest of
  // the span), nothing when the span misses the grid. Missed cells read the zero cell past the
  // grid's end: adding +0 to a sum of scores >= 0 leaves it unchanged. Each node's sum runs over
  // the points in their order, the same number as summed alone; the nodes' sums are independent
  // chains of additions, which the processor overlaps (one sum at a time waits for each
  // addition's latency).
  static constexpr int kBatch = 4;
  void Bounds(Node* nodes, int count, long* scored) const {
    *scored += count;
    const std::size_t n = lattice_.points.size();
    const int level = nodes[0].level;
    const bool leaf = level == 0;
    const int reach = leaf ? 1 : (1 << level) * lattice_.step;
    const float* values =
        leaf ? buffers_.score.data() : buffers_.pools[static_cast<std::size_t>(level - 1)].data();
    std::array<const int*, kBatch> cells{};
    for (int m = 0; m < kBatch; ++m) {
      if (m >= count) {
        cells[static_cast<std::size_t>(m)] = cells[0];  // an unused sum: repeats the first
        continue;
      }
      const Node& node = nodes[m];
      const std::size_t rotation = static_cast<std::size_t>(node.a) * n;
      int* out = buffers_.cells.data() + static_cast<std::size_t>(m) * n;
      internal::BlockCells(std::span<const int>(buffers_.cell_i.data() + rotation, n),
                           std::span<const int>(buffers_.cell_j.data() + rotation, n),
                           node.u0 * lattice_.step, node.v0 * lattice_.step, reach, width_, height_,
                           std::span<int>(out, n));
      cells[static_cast<std::size_t>(m)] = out;
    }
    float sum0 = 0.0F;
    float sum1 = 0.0F;
    float sum2 = 0.0F;
    float sum3 = 0.0F;
    for (std::size_t k = 0; k < n; ++k) {
      sum0 += values[cells[0][k]];
      sum1 += values[cells[1][k]];
      sum2 += values[cells[2][k]];
      sum3 += values[cells[3][k]];
    }
    const std::array<float, kBatch> sums{sum0, sum1, sum2, sum3};
    for (int m = 0; m < count; ++m) {
      nodes[m].bound = sums[static_cast<std::size_t>(m)];
    }
  }

  // Whether every translation of the block lies within the exclusion (a disc and a strip are
  // convex: it is enough that the block's four corners do).
  [[nodiscard]] bool Excluded(const Node& node) const {
    const int last = (1 << node.level) - 1;
    return exclusion_.Contains(node.u0, node.v0) && exclusion_.Contains(node.u0 + last, node.v0) &&
           exclusion_.Contains(node.u0, node.v0 + last) &&
           exclusion_.Contains(node.u0 + last, node.v0 + last);
  }

  // Visits the nodes [begin, end) best bound first (children on the stack: no allocation).
  void Descend(Node* begin, Node* end, Best* best, long* scored) {
    std::sort(begin, end, [](const Node& x, const Node& y) { return x.bound > y.bound; });
    for (const Node* node = begin; node != end; ++node) {
      if (node->bound <= best->score) {
        return;  // sorted: no later node can beat it either
      }
      if (node->level == 0) {
        *best = Best{node->bound, node->a, node->u0, node->v0, true};
        continue;
      }
      std::array<Node, 4> children{};
      int count = 0;
      const int half_size = 1 << (node->level - 1);
      for (int dv = 0; dv < 2; ++dv) {
        for (int du = 0; du < 2; ++du) {
          Node child{node->a, node->level - 1, node->u0 + du * half_size, node->v0 + dv * half_size,
                     0.0F};
          if (child.u0 >= lattice_.side || child.v0 >= lattice_.side || Excluded(child)) {
            continue;
          }
          children[static_cast<std::size_t>(count++)] = child;
        }
      }
      if (count > 0) {
        Bounds(children.data(), count, scored);
      }
      Descend(children.data(), children.data() + count, best, scored);
    }
  }

  const SearchLattice& lattice_;
  int width_;
  int height_;
  int levels_ = 0;
  Buffers& buffers_;  ///< pools: levels 1..levels_ (more may be held, unused).
  Exclusion exclusion_;
};

// The strip of half-width `radius` around the line from the best translation (u, v) through its
// rival's (ru, rv): the poses a rival on that line does not tell apart from the best.
Exclusion RidgeStrip(int u, int v, int ru, int rv, double radius) {
  const double length = std::hypot(ru - u, rv - v);
  return Exclusion{Exclusion::Shape::kStrip, u, v, radius, -(rv - v) / length, (ru - u) / length};
}

// The ridge verdict of an ambiguous search: `off_ridge`, the best score outside the rival's
// `strip`, within max_ambiguity of the best means every look-alike lies on the strip's line.
void JudgeRidge(const Exclusion& strip, double off_ridge, const PriorSearchOptions& options,
                PriorSearchResult& result) {
  result.off_ridge = off_ridge;
  result.ridge = off_ridge <= options.max_ambiguity * result.score;
  if (result.ridge) {
    result.ridge_axis = Eigen::Vector2d(strip.nv, -strip.nu);
  }
}

// The pose of lattice rotation a and translation (u, v): p_a = T * p_b.
Pose2 LatticePose(const SearchLattice& lattice, double resolution, const Pose2& prior, int a, int u,
                  int v, const PriorSearchOptions& options) {
  const double dtheta = (a - lattice.angles / 2) * options.angular_step;
  return Pose2((u - lattice.half) * lattice.step * resolution,
               (v - lattice.half) * lattice.step * resolution, 0.0) *
         prior * Pose2(0.0, 0.0, dtheta);
}

// Scores every pose of the lattice (the exhaustive search, with the exact rival).
PriorSearchResult ScoreWholeLattice(const SearchLattice& lattice, const Grid2D<float>& distance_a,
                                    const Pose2& prior, const PriorSearchOptions& options) {
  PriorSearchResult result;
  const MapLimits& limits = distance_a.Limits();
  const double res = limits.Resolution();
  const int step = lattice.step;
  const int half = lattice.half;
  const int side = lattice.side;
  const int angles = lattice.angles;
  const std::vector<Eigen::Vector2d>& points = lattice.points;
  const int w = limits.Width();
  const int h = limits.Height();
  // Each cell's score once (the same numbers as the points' own: points on unknown cells add
  // +0, which leaves a sum of scores >= 0 unchanged), kept per thread from search to search.
  struct Scratch {
    std::vector<float> score;
  };
  std::vector<float>& score = ThreadScratch<Scratch, Scratch>().score;
  score.resize(distance_a.size());
  internal::TruncatedScores(distance_a.Cells(), static_cast<float>(1.0 / options.truncation),
                            score);
  std::vector<float> scores(static_cast<std::size_t>(angles) * side * side, 0.0F);
  std::vector<int> ci(points.size());
  std::vector<int> cj(points.size());
  for (int a = 0; a < angles; ++a) {
    const double dtheta = (a - angles / 2) * options.angular_step;
    const PointTransform T(prior * Pose2(0.0, 0.0, dtheta));
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector2d c = limits.ToCellCoordinates(T(points[k]));
      ci[k] = static_cast<int>(std::floor(c.x()));
      cj[k] = static_cast<int>(std::floor(c.y()));
    }
    float* slice = scores.data() + static_cast<std::size_t>(a) * side * side;
    for (std::size_t k = 0; k < points.size(); ++k) {
      // Translation (u, v) moves point k to cell (first_i + u step, first_j + v step); the
      // translations that keep it on the grid, computed once instead of tested per pose.
      const int first_i = ci[k] - half * step;
      const int first_j = cj[k] - half * step;
      const int u_begin = std::min(side, internal::FirstStepAtLeast(first_i, step, 0));
      const int u_end = std::min(side, internal::FirstStepAtLeast(first_i, step, w));
      const int v_begin = std::min(side, internal::FirstStepAtLeast(first_j, step, 0));
      const int v_end = std::min(side, internal::FirstStepAtLeast(first_j, step, h));
      for (int v = v_begin; v < v_end; ++v) {
        const int j = first_j + v * step;
        const float* row = score.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(w);
        float* out = slice + static_cast<std::size_t>(v) * side;
        for (int u = u_begin; u < u_end; ++u) {
          out[u] += row[first_i + u * step];
        }
      }
    }
  }
  result.poses = static_cast<long>(scores.size());
  result.scored = result.poses;
  const auto best = std::max_element(scores.begin(), scores.end());
  const auto index = static_cast<int>(best - scores.begin());
  const int best_a = index / (side * side);
  const int best_v = (index / side) % side;
  const int best_u = index % side;
  const double n = static_cast<double>(points.size());
  result.score = *best / n;
  const double distinct_cells = options.distinct_distance / (step * res);
  // The best score of the translations `exclusion` does not contain, and where it lies.
  const auto best_outside = [&](const Exclusion& exclusion, int* at_u, int* at_v) {
    float found = 0.0F;
    for (int a = 0; a < angles; ++a) {
      for (int v = 0; v < side; ++v) {
        for (int u = 0; u < side; ++u) {
          const float s = scores[(static_cast<std::size_t>(a) * side + v) * side + u];
          if (s > found && !exclusion.Contains(u, v)) {
            found = s;
            *at_u = u;
            *at_v = v;
          }
        }
      }
    }
    return found;
  };
  int rival_u = best_u;
  int rival_v = best_v;
  const float rival =
      best_outside(Exclusion{Exclusion::Shape::kDisc, best_u, best_v, distinct_cells, 0.0, 0.0},
                   &rival_u, &rival_v);
  result.rival = rival / n;
  result.T_a_b = LatticePose(lattice, res, prior, best_a, best_u, best_v, options);
  const bool distinct = result.rival <= options.max_ambiguity * result.score;
  if (!distinct && options.ridge_closures) {
    const Exclusion strip = RidgeStrip(best_u, best_v, rival_u, rival_v, distinct_cells);
    int off_u = 0;
    int off_v = 0;
    JudgeRidge(strip, best_outside(strip, &off_u, &off_v) / n, options, result);
  }
  result.ok = result.score >= options.min_score && (distinct || result.ridge);
  return result;
}

}  // namespace

double PriorSearchOptions::WindowXy(double uncertainty_distance) const {
  return std::min(max_window_xy, window_per_m * uncertainty_distance);
}

double PriorSearchOptions::WideWindowXy(double uncertainty_distance) const {
  return std::min(max_window_xy, wide_window_per_m * uncertainty_distance);
}

double PriorSearchOptions::WindowTheta(double uncertainty_distance) const {
  return std::clamp(window_theta_per_m * uncertainty_distance, window_theta,
                    std::max(window_theta, max_window_theta));
}

PriorSearchResult SearchAroundPrior(std::span<const Eigen::Vector2d> points_b,
                                    const Grid2D<float>& distance_a, const Pose2& prior,
                                    double window_xy, double window_theta,
                                    const PriorSearchOptions& options) {
  PriorSearchResult result;
  result.T_a_b = prior;
  if (points_b.empty() || distance_a.size() == 0) {
    return result;
  }
  const double res = distance_a.Limits().Resolution();
  const SearchLattice lattice = MakeLattice(points_b, res, window_xy, window_theta, options);
  result.poses = static_cast<long>(lattice.angles) * lattice.side * lattice.side;
  // The max pools cost a few passes over a's grid per level; a small window is cheaper scored
  // whole (bench_prior_search: below ~2 m the exhaustive search is faster). Same best pose and
  // verdict either way.
  const double pool_work =
      2.0 * (PoolLevels(lattice.side) + 2 * lattice.step) * static_cast<double>(distance_a.size());
  if (static_cast<double>(result.poses) * static_cast<double>(lattice.points.size()) < pool_work) {
    return ScoreWholeLattice(lattice, distance_a, prior, options);
  }
  BranchAndBound search(distance_a, prior, lattice, options);
  const auto n = static_cast<double>(lattice.points.size());
  // Poses below min_score are no match: the search need not find them.
  const float threshold = std::nextafter(static_cast<float>(options.min_score * n), 0.0F);
  const BranchAndBound::Best best = search.Search(threshold, Exclusion{}, &result.scored);
  if (!best.found) {
    return result;
  }
  result.score = static_cast<double>(best.score) / n;
  const double distinct_cells = options.distinct_distance / (lattice.step * res);
  const float ambiguous = static_cast<float>(options.max_ambiguity) * best.score;
  const BranchAndBound::Best rival = search.Search(
      ambiguous, Exclusion{Exclusion::Shape::kDisc, best.u, best.v, distinct_cells, 0.0, 0.0},
      &result.scored);
  result.rival = rival.found ? static_cast<double>(rival.score) / n : 0.0;
  result.T_a_b = LatticePose(lattice, res, prior, best.a, best.u, best.v, options);
  const bool distinct = result.rival <= options.max_ambiguity * result.score;
  if (!distinct && options.ridge_closures) {
    // Rivals only on the line through the best pose and its rival: a ridge (a corridor, a
    // straight road), whose position along the line is unknown and whose heading and offset
    // across it are measured.
    const Exclusion strip = RidgeStrip(best.u, best.v, rival.u, rival.v, distinct_cells);
    const BranchAndBound::Best off = search.Search(ambiguous, strip, &result.scored);
    JudgeRidge(strip, off.found ? static_cast<double>(off.score) / n : 0.0, options, result);
  }
  result.ok = result.score >= options.min_score && (distinct || result.ridge);
  return result;
}

PriorSearchResult SearchAroundPriorExhaustive(std::span<const Eigen::Vector2d> points_b,
                                              const Grid2D<float>& distance_a, const Pose2& prior,
                                              double window_xy, double window_theta,
                                              const PriorSearchOptions& options) {
  if (points_b.empty() || distance_a.size() == 0) {
    PriorSearchResult result;
    result.T_a_b = prior;
    return result;
  }
  const SearchLattice lattice =
      MakeLattice(points_b, distance_a.Limits().Resolution(), window_xy, window_theta, options);
  return ScoreWholeLattice(lattice, distance_a, prior, options);
}
}  // namespace gridslam::loop_closure
