#include "gridslam/features/internal/response_layer.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "gridslam/common/check.hpp"

namespace gridslam::features::internal {
namespace {

// Sum over [c0, c1) × [y0, y1) from the integral-image rows r0 (y0) and r1 (y1).
inline std::int32_t Box(const std::int32_t* r0, const std::int32_t* r1, int c0, int c1) {
  return r1[c1] - r1[c0] - r0[c1] + r0[c0];
}

// The integral-image rows one output row of a filter reads.
struct RowPointers {
  const std::int32_t* ya;  // Dyy: outer lobe rows y − b, y + b + 1; middle y − lo, y + lo + 1
  const std::int32_t* yb;
  const std::int32_t* yc;
  const std::int32_t* yd;
  const std::int32_t* q0;  // Dxx: rows y − l + 1, y + l
  const std::int32_t* q1;
  const std::int32_t* p0;  // Dxy: rows y − l, y, y + 1, y + l + 1
  const std::int32_t* p1;
  const std::int32_t* p2;
  const std::int32_t* p3;
};

RowPointers Rows(const IntegralImage& ii, int y, const FilterGeometry& f) {
  const int l = f.l;
  const int lo = (l - 1) / 2;  // the middle lobe spans [c − lo, c + lo + 1)
  return {ii.Row(y - f.b),   ii.Row(y + f.b + 1), ii.Row(y - lo), ii.Row(y + lo + 1),
          ii.Row(y - l + 1), ii.Row(y + l),       ii.Row(y - l),  ii.Row(y),
          ii.Row(y + 1),     ii.Row(y + l + 1)};
}

// Integer sums of Dxx, Dyy and Dxy at column x (Eq. (4)'s box filters, docs/method.md §2.2):
// Dyy = outer (2l−1) × L box − 3 × middle (2l−1) × l lobe, Dxx its transpose, Dxy the four
// l × l lobes, + top-left and bottom-right.
struct Sums {
  std::int32_t dxx;
  std::int32_t dyy;
  std::int32_t dxy;
};
inline Sums SumsAt(const RowPointers& r, const FilterGeometry& f, int x) {
  const int l = f.l;
  const int b = f.b;
  const int lo = (l - 1) / 2;
  return {Box(r.q0, r.q1, x - b, x + b + 1) - 3 * Box(r.q0, r.q1, x - lo, x + lo + 1),
          Box(r.ya, r.yb, x - l + 1, x + l) - 3 * Box(r.yc, r.yd, x - l + 1, x + l),
          Box(r.p0, r.p1, x - l, x) + Box(r.p2, r.p3, x + 1, x + l + 1) -
              Box(r.p0, r.p1, x + 1, x + l + 1) - Box(r.p2, r.p3, x - l, x)};
}

float Normaliser(const FilterGeometry& f) {
  return 1.0F / (255.0F * static_cast<float>(f.size) * static_cast<float>(f.size));
}

// det(H_approx) of samples k0 .. k1 of one row; kUnitStep makes the loads contiguous so that
// the loop vectorises.
template <bool kUnitStep>
inline __attribute__((always_inline)) void ComputeRow(const RowPointers& r, const FilterGeometry& f,
                                                      int k0, int k1, int step, float norm2,
                                                      float* out) {
  constexpr float kW2 = kDxyWeight * kDxyWeight;
  for (int k = k0; k <= k1; ++k) {
    const Sums s = SumsAt(r, f, kUnitStep ? k : k * step);
    const auto fxx = static_cast<float>(s.dxx);
    const auto fyy = static_cast<float>(s.dyy);
    const auto fxy = static_cast<float>(s.dxy);
    out[k] = (fxx * fyy - kW2 * fxy * fxy) * norm2;
  }
}

// Per-column differences of a filter's integral-image rows for one output row, so that each box
// takes two look-ups instead of four: Box(r0, r1, c0, c1) = V[c1] − V[c0] with V = r1 − r0.
// Dxx = (Q[x+b+1] − Q[x−b]) − 3·(Q[x+lo+1] − Q[x−lo]) with Q = q1 − q0; Dyy = E[x+l] − E[x−l+1]
// with E = (yb − ya) − 3·(yd − yc); Dxy = F[x] − F[x−l] − F[x+l+1] + F[x+1] with
// F = (p1 − p0) − (p3 − p2). Integer sums, exact (no intermediate leaves the int32 range of the
// table's differences), so the same values as SumsAt's.
struct ColumnDifferences {
  std::vector<std::int32_t> q;
  std::vector<std::int32_t> e;
  std::vector<std::int32_t> f;
};

// det(H_approx) of samples k0 .. k1 of a row at unit step: the column differences over the columns
// the filters read, then the responses (both loops vectorise). The unit-step rows of the first
// octave dominate the detector's cost: compiled also for AVX2, picked at load time where the CPU
// has it (GCC/Clang function multi-versioning). The float operations are ComputeRow's.
__attribute__((target_clones("avx2", "default"))) void ComputeUnitStepRow(
    const RowPointers& r, const FilterGeometry& f, int k0, int k1, float norm2, float* out,
    ColumnDifferences& columns) {
  if (k1 < k0) {
    return;
  }
  const int l = f.l;
  const int b = f.b;
  const int lo = (l - 1) / 2;
  // Columns k0 − b .. k1 + b + 1 (b >= l + 1 >= lo + 1: the widest lobe is Dxx's outer box).
  const int c0 = k0 - b;
  const int count = k1 + b + 2 - c0;
  columns.q.resize(static_cast<std::size_t>(count));
  columns.e.resize(static_cast<std::size_t>(count));
  columns.f.resize(static_cast<std::size_t>(count));
  std::int32_t* q = columns.q.data();  // entry j for column c0 + j
  std::int32_t* e = columns.e.data();
  std::int32_t* d = columns.f.data();
  for (int j = 0; j < count; ++j) {
    q[j] = r.q1[c0 + j] - r.q0[c0 + j];
  }
  for (int j = 0; j < count; ++j) {
    e[j] = (r.yb[c0 + j] - r.ya[c0 + j]) - 3 * (r.yd[c0 + j] - r.yc[c0 + j]);
  }
  for (int j = 0; j < count; ++j) {
    d[j] = (r.p1[c0 + j] - r.p0[c0 + j]) - (r.p3[c0 + j] - r.p2[c0 + j]);
  }
  constexpr float kW2 = kDxyWeight * kDxyWeight;
  for (int x = k0; x <= k1; ++x) {
    const int j = x - c0;  // column x
    const auto fxx =
        static_cast<float>((q[j + b + 1] - q[j - b]) - 3 * (q[j + lo + 1] - q[j - lo]));
    const auto fyy = static_cast<float>(e[j + l] - e[j - l + 1]);
    const auto fxy = static_cast<float>(d[j] - d[j - l] - d[j + l + 1] + d[j + 1]);
    out[x] = (fxx * fyy - kW2 * fxy * fxy) * norm2;
  }
}

}  // namespace

// Compiled also for AVX2 (eight samples per compare), picked at load time like ComputeUnitStepRow.
__attribute__((target_clones("avx2", "default"))) std::uint64_t RowCandidates(const float* row,
                                                                              int k, int count,
                                                                              float threshold) {
  std::array<std::uint8_t, kCandidateChunk> pass{};
  const float* v = row + k;
  const auto test = [&](int j) {
    return static_cast<std::uint8_t>((v[j] > threshold) & (v[j] > v[j - 1]) & (v[j] >= v[j + 1]));
  };
  if (count == kCandidateChunk) {  // a fixed trip count: vectorised without a remainder
    for (int j = 0; j < kCandidateChunk; ++j) {
      pass[static_cast<std::size_t>(j)] = test(j);
    }
  } else {
    for (int j = 0; j < count; ++j) {
      pass[static_cast<std::size_t>(j)] = test(j);
    }
  }
  // Eight flags (0 or 1) at a time: one multiply gathers the low bit of every byte of a
  // little-endian word into its top byte (the partial products land on distinct bits).
  static_assert(std::endian::native == std::endian::little);
  std::uint64_t bits = 0;
  for (int g = 0; g < kCandidateChunk / 8; ++g) {
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, pass.data() + static_cast<std::ptrdiff_t>(8 * g), 8);
    bits |= ((bytes * 0x0102040810204080ULL) >> 56) << (8 * g);
  }
  return bits;
}

FilterGeometry Geometry(int filter_size) {
  GRIDSLAM_CHECK(filter_size % 3 == 0 && (filter_size / 3) % 2 == 1 && filter_size >= 9)
      << "filter size " << filter_size << " is not 3l with l odd >= 3";
  return {filter_size, filter_size / 3, (filter_size - 1) / 2};
}

BoxHessian HessianAt(const IntegralImage& integral, int x, int y, const FilterGeometry& filter) {
  const Sums s = SumsAt(Rows(integral, y, filter), filter, x);
  const float norm = Normaliser(filter);
  return {static_cast<float>(s.dxx) * norm, static_cast<float>(s.dyy) * norm,
          static_cast<float>(s.dxy) * norm};
}

void ResponseLayer::Prepare(int filter_size, int width, int height, int step) {
  filter_ = Geometry(filter_size);
  step_ = step;
  nx_ = (width - 1) / step + 1;
  ny_ = (height - 1) / step + 1;
  k0_ = (filter_.b + step - 1) / step;
  k1_ = width - 1 - filter_.b >= 0 ? (width - 1 - filter_.b) / step : -1;
  m0_ = k0_;
  m1_ = height - 1 - filter_.b >= 0 ? (height - 1 - filter_.b) / step : -1;
  const std::size_t needed = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  if (needed > capacity_) {
    det_ = std::make_unique_for_overwrite<float[]>(needed);  // NOLINT(modernize-avoid-c-arrays)
    capacity_ = needed;
  }
}

void ResponseLayer::Compute(const IntegralImage& integral, int filter_size, int step) {
  Prepare(filter_size, integral.width(), integral.height(), step);
  const float norm2 = Normaliser(filter_) * Normaliser(filter_);
  // Steps up to 4: the vectorised unit-step loop over every pixel of the row, then every step-th
  // value, is cheaper than the scalar strided loop.
  constexpr int kMaxDenseStep = 4;
  std::vector<float> dense(step > 1 && step <= kMaxDenseStep ? integral.width() : 0);
  ColumnDifferences columns;
  for (int m = m0_; m <= m1_; ++m) {
    const RowPointers rows = Rows(integral, m * step, filter_);
    float* out = det_.get() + static_cast<std::ptrdiff_t>(m) * nx_;
    if (step == 1) {
      ComputeUnitStepRow(rows, filter_, k0_, k1_, norm2, out, columns);
    } else if (step <= kMaxDenseStep) {
      ComputeUnitStepRow(rows, filter_, k0_ * step, k1_ * step, norm2, dense.data(), columns);
      for (int k = k0_; k <= k1_; ++k) {
        out[k] = dense[static_cast<std::size_t>(k) * static_cast<std::size_t>(step)];
      }
    } else {
      ComputeRow<false>(rows, filter_, k0_, k1_, step, norm2, out);
    }
  }
}

void ResponseLayer::Subsample(const ResponseLayer& finer, int width, int height, int step) {
  GRIDSLAM_CHECK(finer.step_ * 2 == step) << "finer step " << finer.step_ << ", step " << step;
  Prepare(finer.filter_.size, width, height, step);
  // Sample k here is sample 2k there, inside its valid range since the filter is the same.
  for (int m = m0_; m <= m1_; ++m) {
    const float* in = finer.Row(2 * m);
    float* out = det_.get() + static_cast<std::ptrdiff_t>(m) * nx_;
    for (int k = k0_; k <= k1_; ++k) {
      out[k] = in[2 * static_cast<std::ptrdiff_t>(k)];
    }
  }
}

}  // namespace gridslam::features::internal
