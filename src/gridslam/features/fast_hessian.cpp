#include "gridslam/features/fast_hessian.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <utility>

#include "gridslam/common/check.hpp"
#include "gridslam/common/thread_scratch.hpp"
#include "gridslam/features/internal/response_layer.hpp"

namespace gridslam::features {
namespace {

using internal::ResponseLayer;
using Layers = std::vector<ResponseLayer>;
using Sample = std::array<int, 3>;  // (layer i, row m, column k) of one octave

inline const ResponseLayer& LayerAt(const Layers& layers, int i) {
  return layers[static_cast<std::size_t>(i)];
}

// True if layer i's response at (m, k) is the strict maximum of its 3×3×3 neighbourhood, ties
// going to the first in (layer, row, column) order so that a plateau of two yields one.
bool IsLocalMaximum(const Layers& layers, int i, int m, int k) {
  const float v = layers[static_cast<std::size_t>(i)].At(k, m);
  for (int di = -1; di <= 1; ++di) {
    const ResponseLayer& layer = LayerAt(layers, i + di);
    for (int dm = -1; dm <= 1; ++dm) {
      const float* row = layer.Row(m + dm) + k;
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

// True if the largest neighbouring filter fits at every neighbour of sample s, so that the
// 3×3×3 neighbourhood is defined (smaller filters fit wherever a larger one does).
bool HasNeighbourhood(const Layers& layers, const Sample& s) {
  const int n = static_cast<int>(layers.size());
  if (s[0] < 1 || s[0] > n - 2) {
    return false;
  }
  const ResponseLayer& above = LayerAt(layers, s[0] + 1);
  return s[1] > above.m0() && s[1] < above.m1() && s[2] > above.k0() && s[2] < above.k1();
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
  for (std::size_t c = 0; c < 3; ++c) {
    std::array<std::array<double, 3>, 3> ac = a;
    for (std::size_t r = 0; r < 3; ++r) {
      ac[r][c] = rhs[r];
    }
    x[c] = det3(ac) / d;
  }
  return true;
}

// The 3-D quadratic through the 3×3×3 responses around a sample: the offset (x, y, L) of its
// extremum in samples (H·ξ = −∇ by central differences) and its value there.
struct QuadraticFit {
  double value = 0.0;            // response at the sample
  std::array<double, 3> grad{};  // its gradient, per sample
  std::array<double, 3> offset{};
  [[nodiscard]] bool Converged() const {
    return std::abs(offset[0]) <= 0.5 && std::abs(offset[1]) <= 0.5 && std::abs(offset[2]) <= 0.5;
  }
  [[nodiscard]] double Response() const {
    return value + 0.5 * (grad[0] * offset[0] + grad[1] * offset[1] + grad[2] * offset[2]);
  }
};

std::optional<QuadraticFit> FitQuadratic(const Layers& layers, const Sample& s) {
  const auto r = [&](int di, int dm, int dk) -> double {
    return LayerAt(layers, s[0] + di).At(s[2] + dk, s[1] + dm);
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

// Brown & Lowe (2002): fit; while an offset exceeds half a sample, move to the neighbouring
// sample it points to and fit again, at most max_fits times. Two samples that point at each
// other hold the extremum between them: the fit is kept with its offsets clamped to ±0.5.
std::optional<std::pair<Sample, QuadraticFit>> Refine(const Layers& layers, Sample sample,
                                                      int max_fits) {
  Sample previous = {-1, -1, -1};
  for (int fits = 0; fits < max_fits; ++fits) {
    std::optional<QuadraticFit> fit = FitQuadratic(layers, sample);
    if (!fit.has_value()) {
      return std::nullopt;
    }
    if (fit->Converged()) {
      return std::pair{sample, *fit};
    }
    const auto move = [](double d) { return d > 0.5 ? 1 : (d < -0.5 ? -1 : 0); };
    const Sample next = {sample[0] + move(fit->offset[2]), sample[1] + move(fit->offset[1]),
                         sample[2] + move(fit->offset[0])};
    if (next == previous) {
      for (double& d : fit->offset) {
        d = std::clamp(d, -0.5, 0.5);
      }
      return std::pair{sample, *fit};
    }
    if (!HasNeighbourhood(layers, next)) {
      return std::nullopt;
    }
    previous = sample;
    sample = next;
  }
  return std::nullopt;
}

}  // namespace

BoxHessian ComputeBoxHessian(const IntegralImage& integral, int x, int y, int filter_size) {
  const internal::FilterGeometry f = internal::Geometry(filter_size);
  GRIDSLAM_CHECK(x >= f.b && x < integral.width() - f.b && y >= f.b && y < integral.height() - f.b)
      << "filter " << filter_size << " does not fit at (" << x << ", " << y << ")";
  return internal::HessianAt(integral, x, y, f);
}

std::vector<cv::KeyPoint> DetectFastHessian(const IntegralImage& integral,
                                            const SurfOptions& options) {
  const Status valid = options.Validate();
  GRIDSLAM_CHECK(valid.ok()) << valid.error().ToString();
  std::vector<cv::KeyPoint> keypoints;
  if (integral.empty()) {
    return keypoints;
  }
  const int n = options.layers_per_octave;
  const auto threshold = static_cast<float>(options.hessian_threshold);
  // The layers' buffers (several hundred kB each on a key map) are kept per thread from call to
  // call: allocated afresh, every call paid the kernel's page faults for them again. Every value
  // read is written first in the same call (the valid ranges), so nothing leaks between calls.
  struct LayersTag {};
  struct PreviousTag {};
  Layers& layers = ThreadScratch<LayersTag, Layers>();
  Layers& previous = ThreadScratch<PreviousTag, Layers>();
  layers.resize(static_cast<std::size_t>(n));
  previous.resize(static_cast<std::size_t>(n));
  for (int o = 0; o < options.num_octaves; ++o) {
    const int step = options.initial_step << o;
    std::swap(layers, previous);
    for (int i = 0; i < n; ++i) {
      // Layer i of octave o has the filter of layer 2i + 1 of octave o − 1.
      ResponseLayer& layer = layers[static_cast<std::size_t>(i)];
      if (o > 0 && 2 * i + 1 < n) {
        layer.Subsample(LayerAt(previous, 2 * i + 1), integral.width(), integral.height(), step);
      } else {
        layer.Compute(integral, FilterSize(o, i), step);
      }
    }
    const int filter_step = FilterSize(o, 1) - FilterSize(o, 0);
    std::set<Sample> found;
    for (int i = 1; i + 1 < n; ++i) {
      const ResponseLayer& above = LayerAt(layers, i + 1);
      const ResponseLayer& layer = LayerAt(layers, i);
      const int k_begin = above.k0() + 1;
      const int k_end = above.k1() - 1;
      for (int m = above.m0() + 1; m <= above.m1() - 1; ++m) {
        const float* row = layer.Row(m);
        for (int chunk = k_begin; chunk <= k_end; chunk += internal::kCandidateChunk) {
          // The row tests first, for 64 samples at once: most samples fail there, and
          // IsLocalMaximum requires both (the earlier one strictly), so the outcome is the same.
          std::uint64_t bits = internal::RowCandidates(
              row, chunk, std::min(internal::kCandidateChunk, k_end + 1 - chunk), threshold);
          for (; bits != 0; bits &= bits - 1) {
            const int k = chunk + std::countr_zero(bits);
            if (!IsLocalMaximum(layers, i, m, k)) {
              continue;
            }
            const auto refined = Refine(layers, {i, m, k}, options.interpolation_steps);
            if (!refined.has_value() || !(refined->second.Response() > threshold) ||
                !found.insert(refined->first).second) {
              continue;  // unstable, too weak, or another candidate converged to the same sample
            }
            const auto [ci, cm, ck] = refined->first;
            const std::array<double, 3>& offset = refined->second.offset;
            const BoxHessian at = internal::HessianAt(
                integral, ck * step, cm * step, layers[static_cast<std::size_t>(ci)].filter());
            cv::KeyPoint kp;
            kp.pt = cv::Point2f(static_cast<float>((ck + offset[0]) * step),
                                static_cast<float>((cm + offset[1]) * step));
            kp.size = static_cast<float>(FilterSize(o, ci) + offset[2] * filter_step);
            kp.angle = -1.0F;
            kp.response = static_cast<float>(refined->second.Response());
            kp.octave = o;
            kp.class_id = at.Trace() > 0.0F ? 1 : -1;
            keypoints.push_back(kp);
          }
        }
      }
    }
  }
  std::stable_sort(
      keypoints.begin(), keypoints.end(),
      [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.response > b.response; });
  return keypoints;
}

}  // namespace gridslam::features
