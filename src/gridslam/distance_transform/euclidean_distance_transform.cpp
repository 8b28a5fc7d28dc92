#include "gridslam/distance_transform/euclidean_distance_transform.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

#include "gridslam/common/check.hpp"
#include "gridslam/common/thread_scratch.hpp"

namespace gridslam::distance_transform {

void SquaredDistance1D(const float* f, int n, float* d, int32_t* arg, int32_t* v, float* z) {
  // Lower envelope of the parabolas y = (x - p)^2 + f[p] of the finite samples (F&H §3, Algorithm
  // DT(f)); samples that are not finite are skipped rather than carried as a large number.
  int k = -1;
  for (int q = 0; q < n; ++q) {
    const float fq = f[q];
    if (!(fq < kInfinity)) {
      continue;
    }
    const auto qf = static_cast<float>(q);
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInfinity;
      z[1] = kInfinity;
      continue;
    }
    float s = 0.0F;
    while (true) {
      const int p = v[k];
      const auto pf = static_cast<float>(p);
      // Abscissa where the parabola of q overtakes the rightmost parabola of the envelope.
      s = ((fq + qf * qf) - (f[p] + pf * pf)) / (2.0F * qf - 2.0F * pf);
      if (s <= z[k]) {
        --k;  // never below 0: z[0] = -inf
      } else {
        break;
      }
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInfinity;
  }
  if (k < 0) {
    std::fill(d, d + n, kInfinity);
    if (arg != nullptr) {
      std::fill(arg, arg + n, -1);
    }
    return;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    const auto qf = static_cast<float>(q);
    while (z[k + 1] < qf) {
      ++k;
    }
    const int p = v[k];
    const auto dq = static_cast<float>(q - p);
    d[q] = dq * dq + f[p];
    if (arg != nullptr) {
      arg[q] = p;
    }
  }
}

namespace {

constexpr std::int32_t kNoSource = -1;

/// Row pass of the transform without labels, in integers (Meijster, Roerdink, Hesselink 2000,
/// "A general algorithm for computing distance transforms in linear time"): `f` holds the squared
/// column distances (kNoSource: none), `d` receives min_p (x - p)^2 + f[p]. The lower envelope is
/// kept as the first integer column each parabola wins, so no division is rounded; the minimum is
/// the same number the float envelope of SquaredDistance1D finds. False when the row has no
/// source (then `d` is +inf and `arg` untouched).
///
/// Rows of at most kExactSide cells: every number below (q² + f[q] <= 2 · 4095², the products
/// first · den <= 4096 · 8190) fits in 32 bits, and every squared distance is an integer below
/// 2^24, exact in a float.
bool SquaredDistanceRow(const std::int32_t* f, int n, float* d, std::int32_t* arg, std::int32_t* v,
                        std::int32_t* first) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    const std::int32_t fq = f[q];
    if (fq == kNoSource) {
      continue;
    }
    const std::int32_t cq = q * q + fq;
    std::int32_t start = 0;
    while (k >= 0) {
      const std::int32_t p = v[k];
      // q is strictly nearer than p from the column after floor(num / den) on, where their
      // parabolas meet (at that column p, the earlier one, keeps it, as in SquaredDistance1D);
      // p wins no column any more when that is before its first one.
      const std::int32_t num = cq - (p * p + f[p]);
      const std::int32_t den = 2 * (q - p);
      if (num < first[k] * den) {
        --k;
        continue;
      }
      // num >= 0 here: floor(num / den) is the integer quotient.
      start = num / den + 1;
      break;
    }
    if (start >= n) {
      continue;  // q wins no column of the row
    }
    ++k;
    v[k] = q;
    first[k] = start;
  }
  if (k < 0) {
    std::fill(d, d + n, kInfinity);
    return false;  // `arg` untouched
  }
  for (int e = 0; e <= k; ++e) {
    const int end = e < k ? first[e + 1] : n;
    const std::int32_t p = v[e];
    // In floats (a loop that vectorises): dx² and f[p] are integers below 2^24, so the products
    // are exact and the sum is the integer sum rounded once, as its conversion would be.
    const auto fp = static_cast<float>(f[p]);
    for (int x = first[e]; x < end; ++x) {
      const auto dx = static_cast<float>(x - p);
      d[x] = dx * dx + fp;
    }
    if (arg != nullptr) {
      std::fill(arg + first[e], arg + end, p);
    }
  }
  return true;
}

}  // namespace

namespace {

// The integer transform of rows [row0, row1) of the grid into `out` (row1 - row0 rows; labels
// index the whole grid). The column pass reads every row but keeps only the rows asked for; the
// row pass runs on those alone.
void IntegerTransformRows(const std::uint8_t* is_source, int width, int height, int row0, int row1,
                          SquaredDistanceField& out, bool with_nearest, float max_distance) {
  const int rows = row1 - row0;
  const auto num_cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(rows);
  out.width = width;
  out.height = rows;
  out.squared.resize(num_cells);
  if (with_nearest) {
    out.nearest.resize(num_cells);
  } else {
    out.nearest.clear();
  }
  if (num_cells == 0) {
    return;
  }
  const auto w = static_cast<std::size_t>(width);
  const float max_squared = max_distance < kInfinity ? max_distance * max_distance : kInfinity;
  constexpr int kFar = 1 << 28;
  struct LastTag {};
  struct GTag {};
  struct SourceRowTag {};
  struct VTag {};
  struct FirstTag {};
  struct ArgTag {};
  using Ints = std::vector<int32_t>;
  Ints& last = ThreadScratch<LastTag, Ints>();
  Ints& g = ThreadScratch<GTag, Ints>();
  Ints& source_row = ThreadScratch<SourceRowTag, Ints>();
  Ints& v = ThreadScratch<VTag, Ints>();
  Ints& first = ThreadScratch<FirstTag, Ints>();
  Ints& arg = ThreadScratch<ArgTag, Ints>();
  last.assign(w, -kFar);
  g.resize(num_cells);
  v.resize(w);
  first.resize(w);
  if (with_nearest) {
    source_row.resize(num_cells);
    arg.resize(w);
  }
  // Column pass: rows of the nearest source at or below (forward), then the nearer of that and
  // the nearest at or above (backward; ties to the lower row, as the float version); g holds the
  // squared vertical distance, source_row that source's row (with labels). Rows outside
  // [row0, row1) only move the nearest source along.
  for (int j = 0; j < row0; ++j) {
    const std::uint8_t* src = is_source + static_cast<std::size_t>(j) * w;
    for (std::size_t i = 0; i < w; ++i) {
      last[i] = src[i] != 0 ? j : last[i];
    }
  }
  for (int j = row0; j < row1; ++j) {
    const std::uint8_t* src = is_source + static_cast<std::size_t>(j) * w;
    int32_t* row = g.data() + static_cast<std::size_t>(j - row0) * w;
    for (std::size_t i = 0; i < w; ++i) {
      last[i] = src[i] != 0 ? j : last[i];
      row[i] = j - last[i];
    }
  }
  std::fill(last.begin(), last.end(), kFar);
  for (int j = height - 1; j >= row1; --j) {
    const std::uint8_t* src = is_source + static_cast<std::size_t>(j) * w;
    for (std::size_t i = 0; i < w; ++i) {
      last[i] = src[i] != 0 ? j : last[i];
    }
  }
  for (int j = row1 - 1; j >= row0; --j) {
    const std::uint8_t* src = is_source + static_cast<std::size_t>(j) * w;
    int32_t* row = g.data() + static_cast<std::size_t>(j - row0) * w;
    if (with_nearest) {
      int32_t* rows_of = source_row.data() + static_cast<std::size_t>(j - row0) * w;
      for (std::size_t i = 0; i < w; ++i) {
        last[i] = src[i] != 0 ? j : last[i];
        const int32_t below = row[i];
        const int32_t above = last[i] - j;
        rows_of[i] = below <= above ? j - below : last[i];
        const int32_t best = std::min(below, above);
        const auto bf = static_cast<float>(best);
        row[i] = best >= kFar / 2 || !(bf * bf <= max_squared) ? kNoSource : best * best;
      }
    } else if (max_squared < kInfinity) {
      for (std::size_t i = 0; i < w; ++i) {
        last[i] = src[i] != 0 ? j : last[i];
        const int32_t best = std::min(row[i], last[i] - j);
        const auto bf = static_cast<float>(best);
        row[i] = best >= kFar / 2 || !(bf * bf <= max_squared) ? kNoSource : best * best;
      }
    } else {
      for (std::size_t i = 0; i < w; ++i) {
        last[i] = src[i] != 0 ? j : last[i];
        const int32_t best = std::min(row[i], last[i] - j);
        row[i] = best >= kFar / 2 ? kNoSource : best * best;
      }
    }
  }
  for (int j = 0; j < rows; ++j) {
    const std::size_t offset = static_cast<std::size_t>(j) * w;
    float* d = out.squared.data() + offset;
    if (!SquaredDistanceRow(g.data() + offset, width, d, with_nearest ? arg.data() : nullptr,
                            v.data(), first.data())) {
      // No source near the row (frequent in the small regions a field updates): nothing to label
      // or truncate.
      if (with_nearest) {
        std::fill_n(out.nearest.data() + offset, w, -1);
      }
      continue;
    }
    if (with_nearest) {
      int32_t* nearest = out.nearest.data() + offset;
      for (std::size_t i = 0; i < w; ++i) {
        const int32_t p = arg[i];
        nearest[i] = p < 0 ? -1 : source_row[offset + static_cast<std::size_t>(p)] * width + p;
      }
    }
    if (max_squared < kInfinity) {
      for (std::size_t i = 0; i < w; ++i) {
        if (d[i] > max_squared) {
          d[i] = kInfinity;
          if (with_nearest) {
            out.nearest[offset + i] = -1;
          }
        }
      }
    }
  }
}

// On grids whose squared distances are exact in floats: the integer row pass (the same
// distances and nearest sources, about twice as fast; SquaredEuclideanDistanceTransformFloat is
// the float envelope it is tested against).
constexpr int kExactSide = 4096;

}  // namespace

void SquaredEuclideanDistanceTransform(const std::uint8_t* is_source, int width, int height,
                                       SquaredDistanceField& out, bool with_nearest,
                                       float max_distance) {
  GRIDSLAM_CHECK(width >= 0 && height >= 0) << width << "x" << height;
  if (width > kExactSide || height > kExactSide) {
    SquaredEuclideanDistanceTransformFloat(is_source, width, height, out, with_nearest,
                                           max_distance);
    return;
  }
  IntegerTransformRows(is_source, width, height, 0, height, out, with_nearest, max_distance);
}

void SquaredEuclideanDistanceTransformRows(const std::uint8_t* is_source, int width, int height,
                                           int row0, int row1, SquaredDistanceField& out,
                                           bool with_nearest, float max_distance) {
  GRIDSLAM_CHECK(width >= 0 && height >= 0) << width << "x" << height;
  GRIDSLAM_CHECK(0 <= row0 && row0 <= row1 && row1 <= height)
      << "rows [" << row0 << ", " << row1 << ") of " << height;
  if (width <= kExactSide && height <= kExactSide) {
    IntegerTransformRows(is_source, width, height, row0, row1, out, with_nearest, max_distance);
    return;
  }
  SquaredEuclideanDistanceTransformFloat(is_source, width, height, out, with_nearest, max_distance);
  const auto w = static_cast<std::ptrdiff_t>(width);
  out.squared.erase(out.squared.begin() + row1 * w, out.squared.end());
  out.squared.erase(out.squared.begin(), out.squared.begin() + row0 * w);
  if (with_nearest) {
    out.nearest.erase(out.nearest.begin() + row1 * w, out.nearest.end());
    out.nearest.erase(out.nearest.begin(), out.nearest.begin() + row0 * w);
  }
  out.height = row1 - row0;
}

void SquaredEuclideanDistanceTransformFloat(const std::uint8_t* is_source, int width, int height,
                                            SquaredDistanceField& out, bool with_nearest,
                                            float max_distance) {
  GRIDSLAM_CHECK(width >= 0 && height >= 0) << width << "x" << height;
  const auto num_cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  out.width = width;
  out.height = height;
  out.squared.resize(num_cells);
  if (with_nearest) {
    out.nearest.resize(num_cells);
  } else {
    out.nearest.clear();
  }
  if (num_cells == 0) {
    return;
  }
  const auto w = static_cast<std::size_t>(width);
  const float max_squared = max_distance < kInfinity ? max_distance * max_distance : kInfinity;

  // Column pass with two linear scans (the input is binary): vertical distance to the nearest
  // source of the column, kept as a squared value in `g` and its row in `source_row`.
  constexpr int kFar = 1 << 28;
  // Scratch buffers reused across calls (per thread): small regions are updated often.
  thread_local std::vector<int32_t> last;
  thread_local std::vector<int32_t> source_row;
  thread_local std::vector<float> g;
  thread_local std::vector<int32_t> v;
  thread_local std::vector<float> z;
  thread_local std::vector<int32_t> arg;
  last.assign(w, -kFar);
  source_row.resize(num_cells);
  g.resize(num_cells);
  v.resize(w);
  z.resize(w + 1);
  arg.resize(w);
  for (int j = 0; j < height; ++j) {
    const std::uint8_t* src = is_source + static_cast<std::size_t>(j) * w;
    int32_t* row = source_row.data() + static_cast<std::size_t>(j) * w;
    for (std::size_t i = 0; i < w; ++i) {
      last[i] = src[i] != 0 ? j : last[i];
      row[i] = last[i];
    }
  }
  std::fill(last.begin(), last.end(), kFar);
  for (int j = height - 1; j >= 0; --j) {
    const std::uint8_t* src = is_source + static_cast<std::size_t>(j) * w;
    int32_t* row = source_row.data() + static_cast<std::size_t>(j) * w;
    float* grow = g.data() + static_cast<std::size_t>(j) * w;
    for (std::size_t i = 0; i < w; ++i) {
      last[i] = src[i] != 0 ? j : last[i];
      const int32_t below = j - row[i];  // source at or below row j (lower index)
      const int32_t above = last[i] - j;
      const int32_t best = std::min(below, above);
      row[i] = below <= above ? row[i] : last[i];
      const auto bf = static_cast<float>(best);
      const float sq = best >= kFar / 2 ? kInfinity : bf * bf;
      grow[i] = sq <= max_squared ? sq : kInfinity;
    }
  }

  // Row pass: 1-D lower envelope on every row of the column result.
  for (int j = 0; j < height; ++j) {
    const std::size_t offset = static_cast<std::size_t>(j) * w;
    float* d = out.squared.data() + offset;
    SquaredDistance1D(g.data() + offset, width, d, with_nearest ? arg.data() : nullptr, v.data(),
                      z.data());
    if (with_nearest) {
      int32_t* nearest = out.nearest.data() + offset;
      for (std::size_t i = 0; i < w; ++i) {
        const int32_t p = arg[i];
        nearest[i] = p < 0 ? -1 : source_row[offset + static_cast<std::size_t>(p)] * width + p;
      }
    }
    if (max_squared < kInfinity) {
      for (std::size_t i = 0; i < w; ++i) {
        if (d[i] > max_squared) {
          d[i] = kInfinity;
          if (with_nearest) {
            out.nearest[offset + i] = -1;
          }
        }
      }
    }
  }
}

cv::Mat DistanceTransformCells(const cv::Mat& image) {
  GRIDSLAM_CHECK(image.type() == CV_8UC1) << "expects an 8-bit single-channel image";
  const cv::Mat sources = (image == 0);  // 255 where zero
  cv::Mat contiguous = sources.isContinuous() ? sources : sources.clone();
  SquaredDistanceField field;
  SquaredEuclideanDistanceTransform(contiguous.ptr<std::uint8_t>(), image.cols, image.rows, field);
  cv::Mat out(image.rows, image.cols, CV_32F);
  auto* dst = out.ptr<float>();
  for (std::size_t k = 0; k < field.squared.size(); ++k) {
    dst[k] = std::sqrt(field.squared[k]);
  }
  return out;
}

Grid2D<float> DistanceTransformMetres(const Grid2D<std::uint8_t>& is_source) {
  SquaredDistanceField field;
  SquaredEuclideanDistanceTransform(is_source.data(), is_source.Width(), is_source.Height(), field);
  Grid2D<float> out(is_source.Limits(), kInfinity);
  const auto resolution = static_cast<float>(is_source.Limits().Resolution());
  for (std::size_t k = 0; k < field.squared.size(); ++k) {
    out.data()[k] = std::sqrt(field.squared[k]) * resolution;
  }
  return out;
}

cv::Mat DistanceToImage(const cv::Mat& distance, double d_max) {
  GRIDSLAM_CHECK(d_max > 0.0) << "d_max " << d_max;
  GRIDSLAM_CHECK(distance.type() == CV_32F) << "expects CV_32F distances";
  cv::Mat out(distance.rows, distance.cols, CV_8U);
  for (int r = 0; r < distance.rows; ++r) {
    const auto* src = distance.ptr<float>(r);
    auto* dst = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < distance.cols; ++c) {
      const double d = std::min(static_cast<double>(src[c]), d_max);
      dst[c] = cv::saturate_cast<std::uint8_t>(d / d_max * 255.0);
    }
  }
  return out;
}

}  // namespace gridslam::distance_transform
