#include "gridslam/features/surf_descriptor.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "gridslam/common/check.hpp"
#include "gridslam/features/internal/angle_order.hpp"

namespace gridslam::features {
namespace {

struct Haar {
  float dx = 0.0F;
  float dy = 0.0F;
};

// floor(v) as an int without a libm call (no SSE4.1 rounding in the baseline x86-64 target).
inline int FloorToInt(float v) {
  const int t = static_cast<int>(v);
  return static_cast<float>(t) > v ? t - 1 : t;
}

// c ? t : f, chosen by bit masks: a select the vectoriser takes (a conditional float operation
// would stop it, as it might trap) and the compiler keeps branch-free.
inline float Select(bool c, float t, float f) {
  const std::uint32_t mask = 0U - static_cast<std::uint32_t>(c);
  return std::bit_cast<float>((std::bit_cast<std::uint32_t>(t) & mask) |
                              (std::bit_cast<std::uint32_t>(f) & ~mask));
}

// atan2(y, x) within about 1e-5 rad: a minimax polynomial for atan on [0, 1] and the octant
// fix-ups. Used only to order the orientation samples by angle. Branch-free, so that the loop over
// the samples vectorises: the fix-ups are computed always and selected, as is 0 for (0, 0) (where
// z is NaN); each value is the one the branches gave.
inline float FastAtan2(float y, float x) {
  const float ax = std::abs(x);
  const float ay = std::abs(y);
  const float lo = std::min(ax, ay);
  const float hi = std::max(ax, ay);
  const float z = lo / hi;
  const float z2 = z * z;
  float a =
      z *
      (0.99997726F +
       z2 * (-0.33262347F +
             z2 * (0.19354346F + z2 * (-0.11643287F + z2 * (0.05265332F + z2 * -0.01172120F)))));
  constexpr auto kHalfPi = static_cast<float>(std::numbers::pi / 2.0);
  constexpr auto kPi = static_cast<float>(std::numbers::pi);
  a = Select(ay > ax, kHalfPi - a, a);
  a = Select(x < 0.0F, kPi - a, a);
  a = Select(y < 0.0F, -a, a);
  return Select(hi == 0.0F, 0.0F, a);
}

// Haar wavelets where a box leaves the image: the difference of the means of the halves' parts
// inside, scaled to box-sum units; no response where a half lies wholly outside.
Haar ClippedHaar(const IntegralImage& ii, int px, int py, int h) {
  const auto half_area = static_cast<float>(2 * h * h);
  int area_a = 0;
  int area_b = 0;
  Haar r;
  const float right = ii.ClippedBoxMean(px, py - h, px + h, py + h, &area_a);
  const float left = ii.ClippedBoxMean(px - h, py - h, px, py + h, &area_b);
  if (area_a > 0 && area_b > 0) {
    r.dx = (right - left) * half_area;
  }
  const float bottom = ii.ClippedBoxMean(px - h, py, px + h, py + h, &area_a);
  const float top = ii.ClippedBoxMean(px - h, py - h, px + h, py, &area_b);
  if (area_a > 0 && area_b > 0) {
    r.dy = (bottom - top) * half_area;
  }
  return r;
}

// Haar wavelets of side 2h centred on the pixel boundary left of and above pixel (px, py), as box
// sums [intensity · px²]: dx = right − left, dy = bottom − top. Contract: the boxes fit, px − h >=
// 0, py − h >= 0, px + h <= width, py + h <= height.
inline Haar InteriorHaar(const IntegralImage& ii, int px, int py, int h) {
  const std::int32_t* top = ii.Row(py - h);
  const std::int32_t* mid = ii.Row(py);
  const std::int32_t* bot = ii.Row(py + h);
  const int a = px - h;
  const int c = px + h;
  const std::int32_t dx = bot[c] - 2 * bot[px] + bot[a] - top[c] + 2 * top[px] - top[a];
  const std::int32_t dy = bot[c] - bot[a] - 2 * mid[c] + 2 * mid[a] + top[c] - top[a];
  return {static_cast<float>(dx), static_cast<float>(dy)};
}

// The pixel whose top-left boundary is nearest to (cx, cy) (pixel centres at integer coordinates,
// so the boundary left of pixel px lies at px − 0.5). Non-decreasing in cx and cy.
inline int BoundaryPixel(float c) { return FloorToInt(c + 1.0F); }

// True if the wavelets of side 2h fit in the image at every point of [x0, x1] × [y0, y1]: then
// the samples inside need no clipping (BoundaryPixel is monotonic).
inline bool HaarFits(const IntegralImage& ii, float x0, float y0, float x1, float y1, int h) {
  return BoundaryPixel(x0) - h >= 0 && BoundaryPixel(y0) - h >= 0 &&
         BoundaryPixel(x1) + h <= ii.width() && BoundaryPixel(y1) + h <= ii.height();
}

// Haar wavelets of side 2h centred on the top-left boundary of pixel (px, py), clipped where the
// boxes leave the image.
inline Haar HaarAtPixel(const IntegralImage& ii, int px, int py, int h) {
  if (px - h < 0 || py - h < 0 || px + h > ii.width() || py + h > ii.height()) {
    return ClippedHaar(ii, px, py, h);
  }
  return InteriorHaar(ii, px, py, h);
}

// Haar wavelets of side 2h centred on the pixel boundary nearest to (cx, cy), clipped where the
// boxes leave the image.
inline Haar HaarAt(const IntegralImage& ii, float cx, float cy, int h) {
  return HaarAtPixel(ii, BoundaryPixel(cx), BoundaryPixel(cy), h);
}

// Orientation samples: grid points (i, j) [units of s] with i² + j² < 36 and their Gaussian
// weight, σ = 2s (Bay et al. 2008, §4.1).
constexpr int kOrientationRadius = 6;
constexpr int kMaxOrientationSamples = (2 * kOrientationRadius + 1) * (2 * kOrientationRadius + 1);
struct OrientationSample {
  float i;
  float j;
  float weight;
};
struct OrientationPattern {
  std::array<OrientationSample, kMaxOrientationSamples> samples{};
  int count = 0;
  float extent = 0.0F;  // the largest |i| and |j|
  // The same i and j as arrays, for the loops that vectorise.
  std::array<float, kMaxOrientationSamples> i{};
  std::array<float, kMaxOrientationSamples> j{};
};
const OrientationPattern& GetOrientationPattern() {
  static const OrientationPattern pattern = [] {
    OrientationPattern p;
    constexpr double kSigma = 2.0;
    for (int j = -kOrientationRadius; j <= kOrientationRadius; ++j) {
      for (int i = -kOrientationRadius; i <= kOrientationRadius; ++i) {
        if (i * i + j * j < kOrientationRadius * kOrientationRadius) {
          const double w = std::exp(-(i * i + j * j) / (2.0 * kSigma * kSigma));
          p.samples[static_cast<std::size_t>(p.count++)] = {
              static_cast<float>(i), static_cast<float>(j), static_cast<float>(w)};
          p.extent = std::max(p.extent, static_cast<float>(std::abs(i)));
          p.i[static_cast<std::size_t>(p.count - 1)] = static_cast<float>(i);
          p.j[static_cast<std::size_t>(p.count - 1)] = static_cast<float>(j);
        }
      }
    }
    return p;
  }();
  return pattern;
}

// Descriptor samples: 20 × 20 points at ((k − 9.5)s, (m − 9.5)s) and their Gaussian weight,
// σ = 3.3s (Bay et al. 2008, §4.2), in 4 × 4 sub-regions of 5 × 5.
constexpr int kGrid = 20;
constexpr int kRegionSide = 5;
constexpr int kRegionsPerRow = kGrid / kRegionSide;

// The samples of a grid row are taken in slot order j = 4·kk + q for column k = 5q + kk: the
// five slots 4·kk + q of sub-region column q hold its columns in increasing order, and the four
// sub-regions' samples of one kk are adjacent, so that their sums are added as one vector.
constexpr int ColumnOfSlot(int j) {
  return kRegionSide * (j % kRegionsPerRow) + j / kRegionsPerRow;
}
static_assert(ColumnOfSlot(0) == 0 && ColumnOfSlot(kGrid - 1) == kGrid - 1);

// The weights by row m and slot j.
using GridWeights = std::array<float, static_cast<std::size_t>(kGrid) * kGrid>;
const GridWeights& DescriptorWeights() {
  static const GridWeights weights = [] {
    GridWeights w{};
    constexpr double kSigma = 3.3;
    for (int m = 0; m < kGrid; ++m) {
      for (int j = 0; j < kGrid; ++j) {
        const double u = ColumnOfSlot(j) - 9.5;
        const double v = m - 9.5;
        w[static_cast<std::size_t>(m) * kGrid + static_cast<std::size_t>(j)] =
            static_cast<float>(std::exp(-(u * u + v * v) / (2.0 * kSigma * kSigma)));
      }
    }
    return w;
  }();
  return weights;
}

// The rotated sampling grid of one descriptor. Sample (k, m) lies at (u, v) = ((k − 9.5)s,
// (m − 9.5)s) in the keypoint's frame, at x + u·cos − v·sin, y + u·sin + v·cos in the image; the
// terms that depend on k or on m alone are computed once, with the same float operations
// (sums grouped left to right as written), so the coordinates are bit for bit the same. The
// k terms are kept by slot (ColumnOfSlot).
struct DescriptorFrame {
  float co = 1.0F;
  float si = 0.0F;
  std::array<float, kGrid> x_u{};    // x + u_k·cos, by slot
  std::array<float, kGrid> y_u{};    // y + u_k·sin, by slot
  std::array<float, kGrid> v_sin{};  // v_m·sin
  std::array<float, kGrid> v_cos{};  // v_m·cos

  // The image coordinates of the sample in slot j of row m.
  [[nodiscard]] float X(int j, int m) const {
    return x_u[static_cast<std::size_t>(j)] - v_sin[static_cast<std::size_t>(m)];
  }
  [[nodiscard]] float Y(int j, int m) const {
    return y_u[static_cast<std::size_t>(j)] + v_cos[static_cast<std::size_t>(m)];
  }
};

DescriptorFrame MakeDescriptorFrame(float x, float y, float scale, float angle) {
  DescriptorFrame f;
  f.co = std::cos(angle);
  f.si = std::sin(angle);
  for (int j = 0; j < kGrid; ++j) {
    const auto slot = static_cast<std::size_t>(j);
    const float u = (static_cast<float>(ColumnOfSlot(j)) - 9.5F) * scale;
    f.x_u[slot] = x + u * f.co;
    f.y_u[slot] = y + u * f.si;
    const float v = (static_cast<float>(j) - 9.5F) * scale;  // row m = j
    f.v_sin[slot] = v * f.si;
    f.v_cos[slot] = v * f.co;
  }
  return f;
}

// InteriorHaar at the pixels (px[j], py[j]), j < count <= kMaxCount, where the boxes fit: the
// table offsets of the top-left corners first (a loop that vectorises), then the eight look-ups
// each at fixed distances from there. The same integer sums, so the same values.
template <int kMaxCount>
void InteriorHaars(const IntegralImage& ii, const int* px, const int* py, int count, int h,
                   float* dx, float* dy) {
  const int stride = ii.stride();
  std::array<int, kMaxCount> top;  // offset of (px − h, py − h); written before it is read
  for (int j = 0; j < count; ++j) {
    top[static_cast<std::size_t>(j)] = (py[j] - h) * stride + px[j] - h;
  }
  const std::int32_t* table = ii.Row(0);
  const std::ptrdiff_t mid = static_cast<std::ptrdiff_t>(h) * stride;  // rows py, py + h
  const std::ptrdiff_t bot = 2 * mid;
  for (int j = 0; j < count; ++j) {
    const std::int32_t* t =
        table + top[static_cast<std::size_t>(j)];  // px − h, px, px + h: +0, +h, +2h
    const std::int32_t ta = t[0];
    const std::int32_t tp = t[h];
    const std::int32_t tc = t[2 * h];
    const std::int32_t ma = t[mid];
    const std::int32_t mc = t[mid + 2 * h];
    const std::int32_t ba = t[bot];
    const std::int32_t bp = t[bot + h];
    const std::int32_t bc = t[bot + 2 * h];
    dx[j] = static_cast<float>(bc - 2 * bp + ba - tc + 2 * tp - ta);
    dy[j] = static_cast<float>(bc - ba - 2 * mc + 2 * ma + tc - ta);
  }
}

// The rotated, weighted responses of the 20 samples of grid row m, by slot: rx along the
// orientation, ry perpendicular to it. The pixel coordinates first (a loop that vectorises), then
// the wavelets, then the rotation (vectorises too). The coordinates are monotonic along the row, so
// if the wavelets fit at its first and last samples (slots 0 and 19) they fit at all of them and
// none needs the clipping test.
void RowResponses(const IntegralImage& integral, const DescriptorFrame& f, int m, int h,
                  const float* weight, float* rx, float* ry) {
  std::array<int, kGrid> px;  // every array here is written before it is read
  std::array<int, kGrid> py;
  for (int j = 0; j < kGrid; ++j) {
    px[static_cast<std::size_t>(j)] = BoundaryPixel(f.X(j, m));
    py[static_cast<std::size_t>(j)] = BoundaryPixel(f.Y(j, m));
  }
  constexpr std::size_t kLast = kGrid - 1;
  const auto [x0, x1] = std::minmax(px[0], px[kLast]);
  const auto [y0, y1] = std::minmax(py[0], py[kLast]);
  std::array<float, kGrid> dx;
  std::array<float, kGrid> dy;
  if (x0 - h >= 0 && y0 - h >= 0 && x1 + h <= integral.width() && y1 + h <= integral.height()) {
    InteriorHaars<kGrid>(integral, px.data(), py.data(), kGrid, h, dx.data(), dy.data());
  } else {
    for (std::size_t j = 0; j < static_cast<std::size_t>(kGrid); ++j) {
      const Haar r = HaarAtPixel(integral, px[j], py[j], h);
      dx[j] = r.dx;
      dy[j] = r.dy;
    }
  }
  const float co = f.co;
  const float si = f.si;
  for (std::size_t j = 0; j < static_cast<std::size_t>(kGrid); ++j) {
    rx[j] = weight[j] * (dx[j] * co + dy[j] * si);
    ry[j] = weight[j] * (-dx[j] * si + dy[j] * co);
  }
}

// The standard descriptor's sums: (Σrx, Σry, Σ|rx|, Σ|ry|) of each sub-region, its terms in the
// order of its samples by row, then column, as one loop over (m, k) added them. The four
// sub-regions of a band of five rows are summed in locals, lane q for sub-region column q.
void StandardSums(const IntegralImage& integral, const DescriptorFrame& f, int h, float* out) {
  const GridWeights& weights = DescriptorWeights();
  using Lanes = std::array<float, kRegionsPerRow>;
  Lanes sx{};
  Lanes sy{};
  Lanes ax{};
  Lanes ay{};
  for (int m = 0; m < kGrid; ++m) {
    std::array<float, kGrid> rx;  // written by RowResponses
    std::array<float, kGrid> ry;
    RowResponses(integral, f, m, h, weights.data() + static_cast<std::ptrdiff_t>(m) * kGrid,
                 rx.data(), ry.data());
    for (std::size_t kk = 0; kk < static_cast<std::size_t>(kRegionSide); ++kk) {
      for (std::size_t q = 0; q < static_cast<std::size_t>(kRegionsPerRow); ++q) {
        const std::size_t j = kk * kRegionsPerRow + q;
        sx[q] += rx[j];
        sy[q] += ry[j];
        ax[q] += std::abs(rx[j]);
        ay[q] += std::abs(ry[j]);
      }
    }
    if (m % kRegionSide == kRegionSide - 1) {
      for (std::size_t q = 0; q < static_cast<std::size_t>(kRegionsPerRow); ++q) {
        float* d = out + 4 * ((m / kRegionSide) * kRegionsPerRow + static_cast<std::ptrdiff_t>(q));
        d[0] = sx[q];
        d[1] = sy[q];
        d[2] = ax[q];
        d[3] = ay[q];
      }
      sx = {};
      sy = {};
      ax = {};
      ay = {};
    }
  }
}

// The extended descriptor's sums, split by the sign of the other response, added in the same
// order of the samples into `out` (zeroed by the caller).
void ExtendedSums(const IntegralImage& integral, const DescriptorFrame& f, int h, float* out) {
  const GridWeights& weights = DescriptorWeights();
  for (int m = 0; m < kGrid; ++m) {
    std::array<float, kGrid> rx;  // written by RowResponses
    std::array<float, kGrid> ry;
    RowResponses(integral, f, m, h, weights.data() + static_cast<std::ptrdiff_t>(m) * kGrid,
                 rx.data(), ry.data());
    for (int j = 0; j < kGrid; ++j) {
      const float x = rx[static_cast<std::size_t>(j)];
      const float y = ry[static_cast<std::size_t>(j)];
      const int region = (m / kRegionSide) * kRegionsPerRow + j % kRegionsPerRow;
      float* d = out + 8 * static_cast<std::ptrdiff_t>(region);
      const int sx = y < 0.0F ? 0 : 2;
      d[sx] += x;
      d[sx + 1] += std::abs(x);
      const int sy = x < 0.0F ? 4 : 6;
      d[sy] += y;
      d[sy + 1] += std::abs(y);
    }
  }
}

// The samples with a response, in pattern order: the angle of the response and its
// Gaussian-weighted components (structure of arrays, so that the angle loop vectorises; the
// entries from n on are not set).
struct OrientationPoints {
  std::array<float, kMaxOrientationSamples> angle;
  std::array<float, kMaxOrientationSamples> dx;
  std::array<float, kMaxOrientationSamples> dy;
  int n = 0;
};

// Appends the wavelet response of side 2h at each of the pattern's samples around (x, y) that is
// not (0, 0) to `points` (dx, dy) and its weight to `weight`, in pattern order. Each is written
// always and kept (n advanced) only if not (0, 0): no branch to mispredict. kFits: the caller
// checked that the wavelets fit at every sample; then the pixels and the look-ups are loops over
// all samples (InteriorHaars).
template <bool kFits>
int CollectResponses(const IntegralImage& integral, float x, float y, float scale, int h,
                     OrientationPoints& points, float* weight) {
  const OrientationPattern& pattern = GetOrientationPattern();
  const int count = pattern.count;
  std::array<float, kMaxOrientationSamples> dx;  // written before they are read
  std::array<float, kMaxOrientationSamples> dy;
  if constexpr (kFits) {
    std::array<int, kMaxOrientationSamples> px;
    std::array<int, kMaxOrientationSamples> py;
    for (std::size_t s = 0; s < static_cast<std::size_t>(count); ++s) {
      px[s] = BoundaryPixel(x + pattern.i[s] * scale);
      py[s] = BoundaryPixel(y + pattern.j[s] * scale);
    }
    InteriorHaars<kMaxOrientationSamples>(integral, px.data(), py.data(), count, h, dx.data(),
                                          dy.data());
  } else {
    for (std::size_t s = 0; s < static_cast<std::size_t>(count); ++s) {
      const Haar r = HaarAt(integral, x + pattern.i[s] * scale, y + pattern.j[s] * scale, h);
      dx[s] = r.dx;
      dy[s] = r.dy;
    }
  }
  int n = 0;
  for (std::size_t s = 0; s < static_cast<std::size_t>(count); ++s) {
    const auto k = static_cast<std::size_t>(n);
    points.dx[k] = dx[s];
    points.dy[k] = dy[s];
    weight[k] = pattern.samples[s].weight;
    n += dx[s] != 0.0F || dy[s] != 0.0F ? 1 : 0;
  }
  return n;
}

// The wavelet responses of side 2h at the pattern's samples around (x, y): those not (0, 0),
// packed in pattern order, as the angle and the weighted components.
void CollectOrientationPoints(const IntegralImage& integral, float x, float y, float scale, int h,
                              OrientationPoints& points) {
  // The samples' extreme coordinates, computed as theirs: if the wavelets fit there, they fit at
  // every sample and the per-sample clipping test is skipped.
  const float e = GetOrientationPattern().extent;
  const bool fits =
      HaarFits(integral, x + -e * scale, y + -e * scale, x + e * scale, y + e * scale, h);
  std::array<float, kMaxOrientationSamples> weight;  // written before read, like `points`
  const int n = fits ? CollectResponses<true>(integral, x, y, scale, h, points, weight.data())
                     : CollectResponses<false>(integral, x, y, scale, h, points, weight.data());
  for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
    points.angle[k] = FastAtan2(points.dy[k], points.dx[k]);
    points.dx[k] *= weight[k];
    points.dy[k] *= weight[k];
  }
  points.n = n;
}

// The points in ascending angle twice round the circle: entries n .. 2n − 1 repeat the first n
// with 2π added to the angle, so that the sliding window never wraps an index.
struct CircularPoints {
  std::array<float, 2 * kMaxOrientationSamples> angle;
  std::array<float, 2 * kMaxOrientationSamples> dx;
  std::array<float, 2 * kMaxOrientationSamples> dy;
};

// Sorts the points by angle into `circle`. The window sums depend on the order of equal angles, so
// with ties the order is the one std::sort gives the points in pattern order (its result follows
// from the comparisons alone); without ties the ascending order is unique and the bucket sort's.
void SortAroundCircle(const OrientationPoints& points, CircularPoints& circle) {
  static_assert(kMaxOrientationSamples <= internal::kMaxAngleKeys);
  const int n = points.n;
  const auto size = static_cast<std::size_t>(n);
  std::array<std::uint8_t, kMaxOrientationSamples> order;
  if (internal::OrderByAngle(points.angle.data(), n, order.data())) {
    for (std::size_t k = 0; k < size; ++k) {
      circle.angle[k] = points.angle[order[k]];
      circle.dx[k] = points.dx[order[k]];
      circle.dy[k] = points.dy[order[k]];
    }
  } else {
    struct Point {
      float angle;
      float dx;
      float dy;
    };
    std::array<Point, kMaxOrientationSamples> sorted;
    for (std::size_t k = 0; k < size; ++k) {
      sorted[k] = {points.angle[k], points.dx[k], points.dy[k]};
    }
    std::sort(sorted.begin(), sorted.begin() + n,
              [](const Point& a, const Point& b) { return a.angle < b.angle; });
    for (std::size_t k = 0; k < size; ++k) {
      circle.angle[k] = sorted[k].angle;
      circle.dx[k] = sorted[k].dx;
      circle.dy[k] = sorted[k].dy;
    }
  }
  constexpr auto kTwoPi = static_cast<float>(2.0 * std::numbers::pi);
  for (std::size_t k = 0; k < size; ++k) {
    circle.angle[size + k] = circle.angle[k] + kTwoPi;
    circle.dx[size + k] = circle.dx[k];
    circle.dy[size + k] = circle.dy[k];
  }
}

}  // namespace

float AssignOrientation(const IntegralImage& integral, float x, float y, float scale) {
  GRIDSLAM_CHECK(scale > 0.0F) << "scale " << scale;
  const int h = std::max(1, static_cast<int>(std::lround(2.0F * scale)));  // side 4s
  OrientationPoints points;
  CollectOrientationPoints(integral, x, y, scale, h, points);
  if (points.n == 0) {
    return 0.0F;
  }
  CircularPoints circle;
  SortAroundCircle(points, circle);
  // Every distinct window [θ_a, θ_a + π/3): two pointers around the circle.
  constexpr auto kWindow = static_cast<float>(std::numbers::pi / 3.0);
  const int n = points.n;
  double sum_x = 0.0;
  double sum_y = 0.0;
  double best_x = 0.0;
  double best_y = 0.0;
  double best_norm2 = -1.0;
  int e = 0;
  for (int a = 0; a < n; ++a) {
    const float start = circle.angle[static_cast<std::size_t>(a)];
    while (e < a + n && circle.angle[static_cast<std::size_t>(e)] - start < kWindow) {
      sum_x += circle.dx[static_cast<std::size_t>(e)];
      sum_y += circle.dy[static_cast<std::size_t>(e)];
      ++e;
    }
    const double norm2 = sum_x * sum_x + sum_y * sum_y;
    if (norm2 > best_norm2) {
      best_norm2 = norm2;
      best_x = sum_x;
      best_y = sum_y;
    }
    sum_x -= circle.dx[static_cast<std::size_t>(a)];
    sum_y -= circle.dy[static_cast<std::size_t>(a)];
  }
  return static_cast<float>(std::atan2(best_y, best_x));
}

void ComputeSurfDescriptor(const IntegralImage& integral, float x, float y, float scale,
                           float angle, bool extended, float* out) {
  GRIDSLAM_CHECK(scale > 0.0F) << "scale " << scale;
  const int h = std::max(1, static_cast<int>(std::lround(scale)));  // side 2s
  const DescriptorFrame frame = MakeDescriptorFrame(x, y, scale, angle);
  const int size = extended ? kSurfExtendedDescriptorSize : kSurfDescriptorSize;
  std::fill(out, out + size, 0.0F);
  if (extended) {
    ExtendedSums(integral, frame, h, out);
  } else {
    StandardSums(integral, frame, h, out);
  }
  double norm2 = 0.0;
  for (int i = 0; i < size; ++i) {
    norm2 += static_cast<double>(out[i]) * out[i];
  }
  if (norm2 > 0.0) {
    const auto inv = static_cast<float>(1.0 / std::sqrt(norm2));
    for (int i = 0; i < size; ++i) {
      out[i] *= inv;
    }
  }
}

}  // namespace gridslam::features
