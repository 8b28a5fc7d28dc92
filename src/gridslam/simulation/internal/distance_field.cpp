#include "gridslam/simulation/internal/distance_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridslam::simulation::internal {
namespace {

/// One-dimensional squared distance transform of the sampled function f (Felzenszwalb &
/// Huttenlocher, "Distance Transforms of Sampled Functions", Algorithm 1).
void Transform1d(const std::vector<double>& f, int n, std::vector<double>& d, std::vector<int>& v,
                 std::vector<double>& z) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = 1; q < n; ++q) {
    const auto uq = static_cast<std::size_t>(q);
    auto intersection = [&](int p) {
      const auto up = static_cast<std::size_t>(p);
      return ((f[uq] + q * q) - (f[up] + p * p)) / (2.0 * (q - p));
    };
    double s = intersection(v[static_cast<std::size_t>(k)]);
    while (s <= z[static_cast<std::size_t>(k)]) {  // z[0] = -inf ends the loop.
      --k;
      s = intersection(v[static_cast<std::size_t>(k)]);
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = s;
    z[static_cast<std::size_t>(k) + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(k) + 1] < q) {
      ++k;
    }
    const int p = v[static_cast<std::size_t>(k)];
    d[static_cast<std::size_t>(q)] = (q - p) * (q - p) + f[static_cast<std::size_t>(p)];
  }
}

}  // namespace

std::vector<float> DistanceTransform(const std::vector<std::uint8_t>& obstacle, int width,
                                     int height) {
  const auto w = static_cast<std::size_t>(width);
  const auto h = static_cast<std::size_t>(height);
  const double big = static_cast<double>(width + height);
  const double big_sq = big * big;
  std::vector<double> sq(w * h);
  for (std::size_t k = 0; k < sq.size(); ++k) {
    sq[k] = obstacle[k] != 0 ? 0.0 : big_sq;
  }
  const std::size_t n_max = std::max(w, h);
  std::vector<double> f(n_max);
  std::vector<double> d(n_max);
  std::vector<int> v(n_max);
  std::vector<double> z(n_max + 1);
  // Columns, then rows.
  for (std::size_t i = 0; i < w; ++i) {
    for (std::size_t j = 0; j < h; ++j) {
      f[j] = sq[j * w + i];
    }
    Transform1d(f, height, d, v, z);
    for (std::size_t j = 0; j < h; ++j) {
      sq[j * w + i] = d[j];
    }
  }
  std::vector<float> out(w * h);
  for (std::size_t j = 0; j < h; ++j) {
    std::copy(sq.begin() + static_cast<long>(j * w), sq.begin() + static_cast<long>((j + 1) * w),
              f.begin());
    Transform1d(f, width, d, v, z);
    for (std::size_t i = 0; i < w; ++i) {
      out[j * w + i] = static_cast<float>(std::min(std::sqrt(d[i]), big));
    }
  }
  return out;
}

}  // namespace gridslam::simulation::internal
