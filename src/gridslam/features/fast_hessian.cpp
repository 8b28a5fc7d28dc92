#include "gridslam/features/fast_hessian.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>

#include "gridslam/common/check.hpp"

namespace gridslam::features {
namespace {

// Geometry of one filter size: lobe length l = L/3 and half extent b = (L−1)/2.
struct FilterGeometry {
  int size;
  int l;
  int b;
};

FilterGeometry Geometry(int filter_size) {
  GRIDSLAM_CHECK(filter_size % 3 == 0 && (filter_size / 3) % 2 == 1 && filter_size >= 9)
      << "filter size " << filter_size << " is not 3l with l odd >= 3";
  return {filter_size, filter_size / 3, (filter_size - 1) / 2};
}

// det(H_approx) of one layer on the octave's sampling grid (nx × ny samples, sample (k, m) at
// pixel (k·step, m·step)); valid only inside [k0, k1] × [m0, m1], where the filter fits.
struct ResponseLayer {
  FilterGeometry filter{};
  int k0 = 0;
  int k1 = -1;
  int m0 = 0;
  int m1 = -1;
  std::vector<float> det;
};

// Box sums with the four row pointers r0 (y0), r1 (y1) and columns c0 (x0), c1 (x1).
inline std::int32_t Box(const std::int32_t* r0, const std::int32_t* r1, int c0, int c1) {
  return r1[c1] - r1[c0] - r0[c1] + r0[c0];
}

// Eq. (4) with the lobes of reconstruction.md §2.2 for one pixel; sums in integer units.
BoxHessian HessianAt(const IntegralImage& ii, int x, int y, const FilterGeometry& f) {
  const int l = f.l;
  const int b = f.b;
  const int lo = (l - 1) / 2;  // the middle lobe spans [c − lo, c + lo + 1)
  // Dyy: outer (2l−1) × L box minus 3 × the middle (2l−1) × l lobe.
  const std::int32_t dyy = Box(ii.Row(y - b), ii.Row(y + b + 1), x - l + 1, x + l) -
                           3 * Box(ii.Row(y - lo), ii.Row(y + lo + 1), x - l + 1, x + l);
  const std::int32_t* q0 = ii.Row(y - l + 1);
  const std::int32_t* q1 = ii.Row(y + l);
  const std::int32_t dxx = Box(q0, q1, x - b, x + b + 1) - 3 * Box(q0, q1, x - lo, x + lo + 1);
  const std::int32_t* p0 = ii.Row(y - l);
  const std::int32_t* p1 = ii.Row(y);
  const std::int32_t* p2 = ii.Row(y + 1);
  const std::int32_t* p3 = ii.Row(y + l + 1);
  const std::int32_t dxy = Box(p0, p1, x - l, x) + Box(p2, p3, x + 1, x + l + 1) -
                           Box(p0, p1, x + 1, x + l + 1) - Box(p2, p3, x - l, x);
  const float norm = 1.0F / (255.0F * static_cast<float>(f.size) * static_cast<float>(f.size));
  return {static_cast<float>(dxx) * norm, static_cast<float>(dyy) * norm,
          static_cast<float>(dxy) * norm};
}

// det(H_approx) of samples k0 .. k1 of one row, the same arithmetic as HessianAt on the rows'
// pointers. kUnitStep makes the loads contiguous so that the loop vectorises.
struct RowPointers {
  const std::int32_t* ya;  // Dyy outer lobe rows y − b, y + b + 1, middle lobe y − lo, y + lo + 1
  const std::int32_t* yb;
  const std::int32_t* yc;
  const std::int32_t* yd;
  const std::int32_t* q0;  // Dxx rows y − l + 1, y + l
  const std::int32_t* q1;
  const std::int32_t* p0;  // Dxy rows y − l, y, y + 1, y + l + 1
  const std::int32_t* p1;
  const std::int32_t* p2;
  const std::int32_t* p3;
};

template <bool kUnitStep>
void ComputeRow(const RowPointers& r, const FilterGeometry& f, int k0, int k1, int step,
                float norm2, float* out) {
  const int l = f.l;
  const int b = f.b;
  const int lo = (l - 1) / 2;
  const float w2 = kDxyWeight * kDxyWeight;
  for (int k = k0; k <= k1; ++k) {
    const int x = kUnitStep ? k : k * step;
    const std::int32_t dyy =
        Box(r.ya, r.yb, x - l + 1, x + l) - 3 * Box(r.yc, r.yd, x - l + 1, x + l);
    const std::int32_t dxx =
        Box(r.q0, r.q1, x - b, x + b + 1) - 3 * Box(r.q0, r.q1, x - lo, x + lo + 1);
    const std::int32_t dxy = Box(r.p0, r.p1, x - l, x) + Box(r.p2, r.p3, x + 1, x + l + 1) -
                             Box(r.p0, r.p1, x + 1, x + l + 1) - Box(r.p2, r.p3, x - l, x);
    const auto fxx = static_cast<float>(dxx);
    const auto fyy = static_cast<float>(dyy);
    const auto fxy = static_cast<float>(dxy);
    out[k] = (fxx * fyy - w2 * fxy * fxy) * norm2;
  }
}

// Fills `layer` for one octave grid (nx × ny samples at pixels (k·step, m·step)).
void ComputeLayer(const IntegralImage& ii, int step, int nx, int ny, ResponseLayer& layer) {
  const FilterGeometry& f = layer.filter;
  const int w = ii.width();
  const int h = ii.height();
  layer.k0 = (f.b + step - 1) / step;
  layer.k1 = (w - 1 - f.b) >= 0 ? (w - 1 - f.b) / step : -1;
  layer.m0 = (f.b + step - 1) / step;
  layer.m1 = (h - 1 - f.b) >= 0 ? (h - 1 - f.b) / step : -1;
  layer.det.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0.0F);
  const int l = f.l;
  const int lo = (l - 1) / 2;
  const float norm = 1.0F / (255.0F * static_cast<float>(f.size) * static_cast<float>(f.size));
  for (int m = layer.m0; m <= layer.m1; ++m) {
    const int y = m * step;
    const RowPointers rows{ii.Row(y - f.b),   ii.Row(y + f.b + 1), ii.Row(y - lo),
                           ii.Row(y + lo + 1), ii.Row(y - l + 1),   ii.Row(y + l),
                           ii.Row(y - l),      ii.Row(y),           ii.Row(y + 1),
                           ii.Row(y + l + 1)};
    float* out = layer.det.data() + static_cast<std::ptrdiff_t>(m) * nx;
    if (step == 1) {
      ComputeRow<true>(rows, f, layer.k0, layer.k1, step, norm * norm, out);
    } else {
      ComputeRow<false>(rows, f, layer.k0, layer.k1, step, norm * norm, out);
    }
  }
}

// True if `v` at (layer i, row m, column k) is the strict maximum of its 3×3×3 neighbourhood,
// ties going to the first in (layer, row, column) order so that a plateau of two yields one.
bool IsLocalMaximum(const std::vector<ResponseLayer>& layers, int i, int m, int k, int nx) {
  const float v = layers[static_cast<std::size_t>(i)].det[static_cast<std::size_t>(m * nx + k)];
  for (int di = -1; di <= 1; ++di) {
    const std::vector<float>& det = layers[static_cast<std::size_t>(i + di)].det;
    for (int dm = -1; dm <= 1; ++dm) {
      const float* row = det.data() + static_cast<std::ptrdiff_t>(m + dm) * nx + k;
      for (int dk = -1; dk <= 1; ++dk) {
        if (di == 0 && dm == 0 && dk == 0) {
          continue;
        }
        const bool before = di < 0 || (di == 0 && (dm < 0 || (dm == 0 && dk < 0)));
        const float n = row[dk];
        if (before ? !(v > n) : !(v >= n)) {
          return false;
        }
      }
    }
  }
  return true;
}

// Solves the 3×3 system a·x = rhs by Cramer's rule; false if a is (nearly) singular.
bool Solve3(const std::array<std::array<double, 3>, 3>& a, const std::array<double, 3>& rhs,
            std::array<double, 3>& x) {
  const auto det3 = [](const std::array<std::array<double, 3>, 3>& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det3(a);
  if (!(std::abs(d) > 1e-30)) {
    return false;
  }
  for (int c = 0; c < 3; ++c) {
    std::array<std::array<double, 3>, 3> ac = a;
    for (int r = 0; r < 3; ++r) {
      ac[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] = rhs[static_cast<std::size_t>(r)];
    }
    x[static_cast<std::size_t>(c)] = det3(ac) / d;
  }
  return true;
}

// The 3-D quadratic through the 3×3×3 responses around sample (i, m, k): offset (x, y, L) of its
// extremum in samples, solving H·ξ = −∇ with central differences, and the response there.
struct QuadraticFit {
  double value = 0.0;             // response at the sample
  std::array<double, 3> grad{};   // its gradient in samples
  std::array<double, 3> offset{};
  [[nodiscard]] bool Converged() const {
    return std::abs(offset[0]) <= 0.5 && std::abs(offset[1]) <= 0.5 && std::abs(offset[2]) <= 0.5;
  }
  /// The quadratic's value at the offset.
  [[nodiscard]] double Response() const {
    return value + 0.5 * (grad[0] * offset[0] + grad[1] * offset[1] + grad[2] * offset[2]);
  }
};

std::optional<QuadraticFit> FitQuadratic(const std::vector<ResponseLayer>& layers, int i, int m,
                                         int k, int nx) {
  const auto r = [&](int di, int dm, int dk) -> double {
    return layers[static_cast<std::size_t>(i + di)]
        .det[static_cast<std::size_t>((m + dm) * nx + k + dk)];
  };
  const double v = r(0, 0, 0);
  const std::array<double, 3> grad = {(r(0, 0, 1) - r(0, 0, -1)) / 2.0,
                                      (r(0, 1, 0) - r(0, -1, 0)) / 2.0,
                                      (r(1, 0, 0) - r(-1, 0, 0)) / 2.0};
  const double dxx = r(0, 0, 1) + r(0, 0, -1) - 2.0 * v;
  const double dyy = r(0, 1, 0) + r(0, -1, 0) - 2.0 * v;
  const double dss = r(1, 0, 0) + r(-1, 0, 0) - 2.0 * v;
  const double dxy = (r(0, 1, 1) - r(0, 1, -1) - r(0, -1, 1) + r(0, -1, -1)) / 4.0;
  const double dxs = (r(1, 0, 1) - r(1, 0, -1) - r(-1, 0, 1) + r(-1, 0, -1)) / 4.0;
  const double dys = (r(1, 1, 0) - r(1, -1, 0) - r(-1, 1, 0) + r(-1, -1, 0)) / 4.0;
  const std::array<std::array<double, 3>, 3> hess = {
      {{dxx, dxy, dxs}, {dxy, dyy, dys}, {dxs, dys, dss}}};
  QuadraticFit fit{v, grad, {}};
  if (!Solve3(hess, {-grad[0], -grad[1], -grad[2]}, fit.offset)) {
    return std::nullopt;
  }
  return fit;
}

// A candidate sample (layer i, row m, column k) of one octave and the fit that locates it.
struct Refined {
  std::array<int, 3> sample;  // (i, m, k)
  QuadraticFit fit;
};

// Brown & Lowe (2002): fit; while an offset exceeds half a sample, move to the neighbouring
// sample it points to and fit again, at most max_fits times. Two samples that point at each
// other hold the extremum between them: their fit is kept with the offsets clamped to ±0.5.
std::optional<Refined> Refine(const std::vector<ResponseLayer>& layers, std::array<int, 3> sample,
                              int nx, int max_fits) {
  const int n = static_cast<int>(layers.size());
  std::array<int, 3> previous = {-1, -1, -1};
  for (int fits = 0; fits < max_fits; ++fits) {
    std::optional<QuadraticFit> fit = FitQuadratic(layers, sample[0], sample[1], sample[2], nx);
    if (!fit.has_value()) {
      return std::nullopt;
    }
    if (fit->Converged()) {
      return Refined{sample, *fit};
    }
    const auto move = [](double d) { return d > 0.5 ? 1 : (d < -0.5 ? -1 : 0); };
    const std::array<int, 3> next = {sample[0] + move(fit->offset[2]),
                                     sample[1] + move(fit->offset[1]),
                                     sample[2] + move(fit->offset[0])};
    if (next == previous) {
      for (double& d : fit->offset) {
        d = std::clamp(d, -0.5, 0.5);
      }
      return Refined{sample, *fit};
    }
    // The largest neighbouring filter must fit around the new sample, as for a candidate.
    if (next[0] < 1 || next[0] > n - 2) {
      return std::nullopt;
    }
    const ResponseLayer& above = layers[static_cast<std::size_t>(next[0] + 1)];
    if (next[1] <= above.m0 || next[1] >= above.m1 || next[2] <= above.k0 ||
        next[2] >= above.k1) {
      return std::nullopt;
    }
    previous = sample;
    sample = next;
  }
  return std::nullopt;
}

}  // namespace

BoxHessian ComputeBoxHessian(const IntegralImage& integral, int x, int y, int filter_size) {
  const FilterGeometry f = Geometry(filter_size);
  GRIDSLAM_CHECK(x >= f.b && x < integral.width() - f.b && y >= f.b &&
                 y < integral.height() - f.b)
      << "filter " << filter_size << " does not fit at (" << x << ", " << y << ")";
  return HessianAt(integral, x, y, f);
}

std::vector<cv::KeyPoint> DetectFastHessian(const IntegralImage& integral,
                                            const SurfOptions& options) {
  const Status valid = options.Validate();
  GRIDSLAM_CHECK(valid.ok()) << valid.error().ToString();
  std::vector<cv::KeyPoint> keypoints;
  if (integral.empty()) {
    return keypoints;
  }
  const int w = integral.width();
  const int h = integral.height();
  const auto threshold = static_cast<float>(options.hessian_threshold);
  std::vector<ResponseLayer> layers(static_cast<std::size_t>(options.layers_per_octave));
  for (int o = 0; o < options.num_octaves; ++o) {
    const int step = options.initial_step << o;
    const int nx = (w - 1) / step + 1;
    const int ny = (h - 1) / step + 1;
    for (int i = 0; i < options.layers_per_octave; ++i) {
      ResponseLayer& layer = layers[static_cast<std::size_t>(i)];
      layer.filter = Geometry(FilterSize(o, i));
      ComputeLayer(integral, step, nx, ny, layer);
    }
    const int filter_step = FilterSize(o, 1) - FilterSize(o, 0);
    std::set<std::array<int, 3>> visited;
    for (int i = 1; i + 1 < options.layers_per_octave; ++i) {
      // The largest neighbouring filter must fit at every neighbour of a candidate.
      const ResponseLayer& above = layers[static_cast<std::size_t>(i + 1)];
      const std::vector<float>& det = layers[static_cast<std::size_t>(i)].det;
      for (int m = above.m0 + 1; m <= above.m1 - 1; ++m) {
        for (int k = above.k0 + 1; k <= above.k1 - 1; ++k) {
          const float v = det[static_cast<std::size_t>(m * nx + k)];
          if (!(v > threshold) || !IsLocalMaximum(layers, i, m, k, nx)) {
            continue;
          }
          const std::optional<Refined> refined =
              Refine(layers, {i, m, k}, nx, options.interpolation_steps);
          if (!refined.has_value() || !(refined->fit.Response() > threshold) ||
              !visited.insert(refined->sample).second) {
            continue;  // unstable, too weak, or another candidate converged to the same sample
          }
          const auto [ci, cm, ck] = refined->sample;
          const std::array<double, 3>& offset = refined->fit.offset;
          const BoxHessian at = HessianAt(integral, ck * step, cm * step,
                                          layers[static_cast<std::size_t>(ci)].filter);
          cv::KeyPoint kp;
          kp.pt = cv::Point2f(static_cast<float>((ck + offset[0]) * step),
                              static_cast<float>((cm + offset[1]) * step));
          kp.size = static_cast<float>(FilterSize(o, ci) + offset[2] * filter_step);
          kp.angle = -1.0F;
          kp.response = static_cast<float>(refined->fit.Response());
          kp.octave = o;
          kp.class_id = at.Trace() > 0.0F ? 1 : -1;
          keypoints.push_back(kp);
        }
      }
    }
  }
  std::stable_sort(keypoints.begin(), keypoints.end(),
                   [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.response > b.response; });
  return keypoints;
}

}  // namespace gridslam::features
