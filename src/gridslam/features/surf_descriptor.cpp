#include "gridslam/features/surf_descriptor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "gridslam/common/check.hpp"

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

// atan2(y, x) within about 1e-5 rad: a minimax polynomial for atan on [0, 1] and the octant
// fix-ups. Used only to order the orientation samples by angle.
inline float FastAtan2(float y, float x) {
  const float ax = std::abs(x);
  const float ay = std::abs(y);
  const float lo = std::min(ax, ay);
  const float hi = std::max(ax, ay);
  if (hi == 0.0F) {
    return 0.0F;
  }
  const float z = lo / hi;
  const float z2 = z * z;
  float a =
      z *
      (0.99997726F +
       z2 * (-0.33262347F +
             z2 * (0.19354346F + z2 * (-0.11643287F + z2 * (0.05265332F + z2 * -0.01172120F)))));
  constexpr auto kHalfPi = static_cast<float>(std::numbers::pi / 2.0);
  constexpr auto kPi = static_cast<float>(std::numbers::pi);
  if (ay > ax) {
    a = kHalfPi - a;
  }
  if (x < 0.0F) {
    a = kPi - a;
  }
  return y < 0.0F ? -a : a;
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

// Haar wavelets of side 2h centred on the pixel boundary nearest to (cx, cy) (pixel centres at
// integer coordinates, so the boundary left of pixel px lies at px − 0.5): dx = right − left,
// dy = bottom − top, as box sums [intensity · px²].
inline Haar HaarAt(const IntegralImage& ii, float cx, float cy, int h) {
  const int px = FloorToInt(cx + 1.0F);
  const int py = FloorToInt(cy + 1.0F);
  if (px - h < 0 || py - h < 0 || px + h > ii.width() || py + h > ii.height()) {
    return ClippedHaar(ii, px, py, h);
  }
  const std::int32_t* top = ii.Row(py - h);
  const std::int32_t* mid = ii.Row(py);
  const std::int32_t* bot = ii.Row(py + h);
  const int a = px - h;
  const int c = px + h;
  const std::int32_t dx = bot[c] - 2 * bot[px] + bot[a] - top[c] + 2 * top[px] - top[a];
  const std::int32_t dy = bot[c] - bot[a] - 2 * mid[c] + 2 * mid[a] + top[c] - top[a];
  return {static_cast<float>(dx), static_cast<float>(dy)};
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
        }
      }
    }
    return p;
  }();
  return pattern;
}

// Descriptor samples: 20 × 20 points at ((k − 9.5)s, (m − 9.5)s) and their Gaussian weight,
// σ = 3.3s (Bay et al. 2008, §4.2).
constexpr int kGrid = 20;
using GridWeights = std::array<float, static_cast<std::size_t>(kGrid) * kGrid>;
const GridWeights& DescriptorWeights() {
  static const GridWeights weights = [] {
    GridWeights w{};
    constexpr double kSigma = 3.3;
    for (int m = 0; m < kGrid; ++m) {
      for (int k = 0; k < kGrid; ++k) {
        const double u = k - 9.5;
        const double v = m - 9.5;
        w[static_cast<std::size_t>(m) * kGrid + static_cast<std::size_t>(k)] =
            static_cast<float>(std::exp(-(u * u + v * v) / (2.0 * kSigma * kSigma)));
      }
    }
    return w;
  }();
  return weights;
}

}  // namespace

float AssignOrientation(const IntegralImage& integral, float x, float y, float scale) {
  GRIDSLAM_CHECK(scale > 0.0F) << "scale " << scale;
  const OrientationPattern& pattern = GetOrientationPattern();
  const int h = std::max(1, static_cast<int>(std::lround(2.0F * scale)));  // side 4s
  struct Point {
    float angle;
    float dx;
    float dy;
  };
  std::array<Point, kMaxOrientationSamples> points{};
  int n = 0;
  for (int s = 0; s < pattern.count; ++s) {
    const OrientationSample& p = pattern.samples[static_cast<std::size_t>(s)];
    const Haar r = HaarAt(integral, x + p.i * scale, y + p.j * scale, h);
    if (r.dx == 0.0F && r.dy == 0.0F) {
      continue;
    }
    points[static_cast<std::size_t>(n++)] = {FastAtan2(r.dy, r.dx), r.dx * p.weight,
                                             r.dy * p.weight};
  }
  if (n == 0) {
    return 0.0F;
  }
  std::sort(points.begin(), points.begin() + n,
            [](const Point& a, const Point& b) { return a.angle < b.angle; });
  // Every distinct window [θ_a, θ_a + π/3): two pointers around the circle.
  constexpr auto kWindow = static_cast<float>(std::numbers::pi / 3.0);
  constexpr auto kTwoPi = static_cast<float>(2.0 * std::numbers::pi);
  const auto at = [&](int e) -> const Point& { return points[static_cast<std::size_t>(e % n)]; };
  double sum_x = 0.0;
  double sum_y = 0.0;
  double best_x = 0.0;
  double best_y = 0.0;
  double best_norm2 = -1.0;
  int e = 0;
  for (int a = 0; a < n; ++a) {
    const float start = at(a).angle;
    while (e < a + n && at(e).angle + (e >= n ? kTwoPi : 0.0F) - start < kWindow) {
      sum_x += at(e).dx;
      sum_y += at(e).dy;
      ++e;
    }
    const double norm2 = sum_x * sum_x + sum_y * sum_y;
    if (norm2 > best_norm2) {
      best_norm2 = norm2;
      best_x = sum_x;
      best_y = sum_y;
    }
    sum_x -= at(a).dx;
    sum_y -= at(a).dy;
  }
  return static_cast<float>(std::atan2(best_y, best_x));
}

void ComputeSurfDescriptor(const IntegralImage& integral, float x, float y, float scale,
                           float angle, bool extended, float* out) {
  GRIDSLAM_CHECK(scale > 0.0F) << "scale " << scale;
  const GridWeights& weights = DescriptorWeights();
  const int h = std::max(1, static_cast<int>(std::lround(scale)));  // side 2s
  const float co = std::cos(angle);
  const float si = std::sin(angle);
  const int size = extended ? kSurfExtendedDescriptorSize : kSurfDescriptorSize;
  std::fill(out, out + size, 0.0F);
  for (int m = 0; m < kGrid; ++m) {
    const float v = (static_cast<float>(m) - 9.5F) * scale;
    for (int k = 0; k < kGrid; ++k) {
      const float u = (static_cast<float>(k) - 9.5F) * scale;
      const Haar r = HaarAt(integral, x + u * co - v * si, y + u * si + v * co, h);
      const float w = weights[static_cast<std::size_t>(m) * kGrid + static_cast<std::size_t>(k)];
      const float rx = w * (r.dx * co + r.dy * si);   // along the orientation
      const float ry = w * (-r.dx * si + r.dy * co);  // perpendicular to it
      const int region = (m / 5) * 4 + k / 5;
      if (!extended) {
        float* d = out + 4 * static_cast<std::ptrdiff_t>(region);
        d[0] += rx;
        d[1] += ry;
        d[2] += std::abs(rx);
        d[3] += std::abs(ry);
      } else {
        float* d = out + 8 * static_cast<std::ptrdiff_t>(region);
        const int sx = ry < 0.0F ? 0 : 2;
        d[sx] += rx;
        d[sx + 1] += std::abs(rx);
        const int sy = rx < 0.0F ? 4 : 6;
        d[sy] += ry;
        d[sy + 1] += std::abs(ry);
      }
    }
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
