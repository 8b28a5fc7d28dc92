#include "gridslam/quality/quality_image.hpp"

#include <algorithm>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "gridslam/common/parallel.hpp"
#include "gridslam/grid/log_odds.hpp"

namespace gridslam::quality {

namespace {

constexpr int kTile = TiledGrid<float>::kTileSize;

/// The cells [i0, i0 + n) of row j of `grid`, reflected at the grid's edges (BORDER_REFLECT_101).
void ReflectedRow(const TiledGrid<float>& grid, int i0, int n, int j, float* out) {
  const int width = grid.Width();
  const int jj = cv::borderInterpolate(j, grid.Height(), cv::BORDER_REFLECT_101);
  const int begin = std::clamp(i0, 0, width);
  const int end = std::clamp(i0 + n, begin, width);
  for (int m = 0; m < n; ++m) {
    const int i = i0 + m;
    if (i < begin || i >= end) {
      out[m] = grid.Get(cv::borderInterpolate(i, width, cv::BORDER_REFLECT_101), jj);
    }
  }
  grid.CopyRow(jj, begin, end, out + (begin - i0));
}

}  // namespace

TiledGrid<float> DisagreementShare(const SelfCheckResult& result, const SelfCheckOptions& options,
                                   float min_returns, int threads) {
  const TiledGrid<float>& returns = result.returns_per_cell;
  const TiledGrid<float>& disagreeing = result.disagreeing_per_cell;
  const MapLimits& limits = returns.Limits();
  TiledGrid<float> share(limits, -1.0F);
  if (limits.NumCells() == 0) {
    return share;
  }
  const double sigma = options.heat_radius / limits.Resolution();
  // cv::GaussianBlur's kernel for float images; no smoothing without a radius.
  const int ksize = sigma > 0.0 ? (cvRound(sigma * 4 * 2 + 1) | 1) : 1;
  std::vector<float> kernel(static_cast<std::size_t>(ksize), 1.0F);
  if (ksize > 1) {
    const cv::Mat k = cv::getGaussianKernel(ksize, sigma, CV_32F);
    for (int m = 0; m < ksize; ++m) {
      kernel[static_cast<std::size_t>(m)] = k.at<float>(m);
    }
  }
  const int r = ksize / 2;
  // Tiles within the kernel's reach of a tile with returns.
  const int reach = (r + kTile - 1) / kTile;
  std::vector<bool> needed(static_cast<std::size_t>(returns.TilesX()) * returns.TilesY(), false);
  for (int tj = 0; tj < returns.TilesY(); ++tj) {
    for (int ti = 0; ti < returns.TilesX(); ++ti) {
      if (returns.Tile(ti, tj) == nullptr) {
        continue;
      }
      for (int nj = std::max(0, tj - reach); nj <= std::min(returns.TilesY() - 1, tj + reach);
           ++nj) {
        for (int ni = std::max(0, ti - reach); ni <= std::min(returns.TilesX() - 1, ti + reach);
             ++ni) {
          needed[static_cast<std::size_t>(nj) * returns.TilesX() + ni] = true;
        }
      }
    }
  }
  // Separable filter, rows then columns, each output cell summed over the kernel in order: the
  // value of a cell does not depend on the tiles around it, nor on which thread computes it.
  std::vector<int> tiles;
  for (int t = 0; t < static_cast<int>(needed.size()); ++t) {
    if (needed[static_cast<std::size_t>(t)]) {
      tiles.push_back(t);
    }
  }
  const int span = kTile + 2 * r;
  // Returns fall on walls: most rows of a tile hold none. A term whose input is 0 adds exactly 0
  // to a sum of non-negative terms, so the passes below visit the non-zero inputs only, in the
  // order of the kernel taps, and give the full convolution's numbers bit for bit.
  const auto smooth = [&](std::size_t begin, std::size_t end) {
    std::vector<float> row_r(static_cast<std::size_t>(span));
    std::vector<float> row_d(static_cast<std::size_t>(span));
    std::vector<float> h_r(static_cast<std::size_t>(span) * kTile);
    std::vector<float> h_d(static_cast<std::size_t>(span) * kTile);
    std::vector<char> h_nonzero(static_cast<std::size_t>(span));
    std::vector<int> nonzero;
    std::vector<float> v_r(static_cast<std::size_t>(kTile));
    std::vector<float> v_d(static_cast<std::size_t>(kTile));
    for (std::size_t n = begin; n < end; ++n) {
      const int ti = tiles[n] % returns.TilesX();
      const int tj = tiles[n] / returns.TilesX();
      const int i0 = ti * kTile;
      const int j0 = tj * kTile;
      const int w = std::min(limits.Width(), i0 + kTile) - i0;
      const int h = std::min(limits.Height(), j0 + kTile) - j0;
      for (int y = 0; y < h + 2 * r; ++y) {
        ReflectedRow(returns, i0 - r, w + 2 * r, j0 - r + y, row_r.data());
        ReflectedRow(disagreeing, i0 - r, w + 2 * r, j0 - r + y, row_d.data());
        nonzero.clear();
        for (int p = 0; p < w + 2 * r; ++p) {
          if (row_r[static_cast<std::size_t>(p)] != 0.0F ||
              row_d[static_cast<std::size_t>(p)] != 0.0F) {
            nonzero.push_back(p);
          }
        }
        h_nonzero[static_cast<std::size_t>(y)] = nonzero.empty() ? 0 : 1;
        if (nonzero.empty()) {
          continue;
        }
        float* out_r = h_r.data() + static_cast<std::size_t>(y) * kTile;
        float* out_d = h_d.data() + static_cast<std::size_t>(y) * kTile;
        std::fill(out_r, out_r + w, 0.0F);
        std::fill(out_d, out_d + w, 0.0F);
        for (int m = 0; m < ksize; ++m) {
          const float c = kernel[static_cast<std::size_t>(m)];
          for (const int p : nonzero) {
            const int x = p - m;
            if (x >= 0 && x < w) {
              out_r[x] += c * row_r[static_cast<std::size_t>(p)];
              out_d[x] += c * row_d[static_cast<std::size_t>(p)];
            }
          }
        }
      }
      float* out = nullptr;  // the share's tile, allocated at its first cell with returns
      for (int y = 0; y < h; ++y) {
        bool any = false;
        for (int m = 0; m < ksize && !any; ++m) {
          any = h_nonzero[static_cast<std::size_t>(y + m)] != 0;
        }
        if (!any && min_returns > 0.0F) {
          continue;  // every smoothed count is 0 < min_returns: the share stays -1
        }
        std::fill(v_r.begin(), v_r.end(), 0.0F);
        std::fill(v_d.begin(), v_d.end(), 0.0F);
        for (int m = 0; m < ksize; ++m) {
          if (h_nonzero[static_cast<std::size_t>(y + m)] == 0) {
            continue;
          }
          const float c = kernel[static_cast<std::size_t>(m)];
          const float* in_r = h_r.data() + static_cast<std::size_t>(y + m) * kTile;
          const float* in_d = h_d.data() + static_cast<std::size_t>(y + m) * kTile;
          for (int x = 0; x < w; ++x) {
            v_r[static_cast<std::size_t>(x)] += c * in_r[x];
            v_d[static_cast<std::size_t>(x)] += c * in_d[x];
          }
        }
        for (int x = 0; x < w; ++x) {
          const float rr = v_r[static_cast<std::size_t>(x)];
          if (rr >= min_returns) {
            // Tiles are allocated slot by slot: threads write disjoint tiles of a fixed table.
            out = out != nullptr ? out : share.MutableTile(ti, tj);
            out[TiledGrid<float>::InTile(i0 + x, j0 + y)] =
                std::clamp(v_d[static_cast<std::size_t>(x)] / rr, 0.0F, 1.0F);
          }
        }
      }
    }
  };
  RunParts(tiles.size(), PartCount(tiles.size(), threads),
           [&](std::size_t /*part*/, std::size_t begin, std::size_t end) { smooth(begin, end); });
  return share;
}

namespace {

/// Row j of `grid` over cells [0, width) (`outside` beyond the grid's limits).
void GridRow(const TiledGrid<float>& grid, int j, int width, float outside, float* out) {
  const int inside = j >= 0 && j < grid.Height() ? std::min(width, grid.Width()) : 0;
  grid.CopyRow(j, 0, inside, out);
  std::fill(out + inside, out + width, outside);
}

/// `occupancy_row(j, cells, scratch)` writes the occupancy of map row j into cells[0, width)
/// (scratch: `width` floats of its own). Rows are cut into `threads` parts.
template <class OccupancyRow>
void Render(const MapLimits& limits, OccupancyRow occupancy_row, const TiledGrid<float>& share,
            int threads, cv::Mat& image) {
  const int width = limits.Width();
  const int height = limits.Height();
  image.create(height, width, CV_8UC3);
  const auto render = [&](std::size_t begin, std::size_t end) {
    std::vector<signed char> cells(static_cast<std::size_t>(width));
    std::vector<float> shares(static_cast<std::size_t>(width));
    std::vector<float> scratch(static_cast<std::size_t>(width));
    for (auto j = static_cast<int>(begin); j < static_cast<int>(end); ++j) {
      occupancy_row(j, cells.data(), scratch.data());
      GridRow(share, j, width, -1.0F, shares.data());
      auto* row = image.ptr<cv::Vec3b>(height - 1 - j);
      for (int i = 0; i < width; ++i) {
        const signed char v = cells[static_cast<std::size_t>(i)];
        const double g = v == kOccupiedCell ? 0.0 : (v == kFreeCell ? 255.0 : 205.0);
        const float s = shares[static_cast<std::size_t>(i)];
        if (!(s > 0.0F)) {
          const auto grey = static_cast<std::uint8_t>(g);
          row[i] = cv::Vec3b(grey, grey, grey);
          continue;
        }
        const double a = std::min(1.0, 2.0 * s);
        // Blend towards pure red (BGR 0, 0, 255); walls stay dark enough to read.
        const auto blue = static_cast<std::uint8_t>((1.0 - a) * g);
        const auto red = static_cast<std::uint8_t>((1.0 - a) * g + a * 255.0);
        row[i] = cv::Vec3b(blue, blue, red);
      }
    }
  };
  const auto rows = static_cast<std::size_t>(height);
  RunParts(rows, PartCount(rows, threads),
           [&](std::size_t /*part*/, std::size_t begin, std::size_t end) { render(begin, end); });
}

}  // namespace

cv::Mat RenderQualityImage(const OccupancyImage& map, const TiledGrid<float>& share, int threads) {
  cv::Mat image;
  Render(
      map.Limits(),
      [&](int j, signed char* cells, float* /*scratch*/) {
        const signed char* row = &map.Cells()[static_cast<std::size_t>(j) * map.Width()];
        std::copy(row, row + map.Width(), cells);
      },
      share, threads, image);
  return image;
}

void RenderQualityImage(const TiledGrid<float>& log_odds, const fusion::FusionOptions& fusion,
                        const TiledGrid<float>& share, int threads, cv::Mat& image) {
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(fusion.occupied_probability));
  const auto free = static_cast<float>(ProbabilityToLogOdds(fusion.free_probability));
  Render(
      log_odds.Limits(),
      [&](int j, signed char* cells, float* values) {
        GridRow(log_odds, j, log_odds.Width(), log_odds.Fill(), values);
        for (int i = 0; i < log_odds.Width(); ++i) {
          const float l = values[i];
          cells[i] = l > occupied ? kOccupiedCell : (l < free ? kFreeCell : kUnknownCell);
        }
      },
      share, threads, image);
}

cv::Mat RenderQualityImage(const TiledGrid<float>& log_odds, const fusion::FusionOptions& fusion,
                           const TiledGrid<float>& share, int threads) {
  cv::Mat image;
  RenderQualityImage(log_odds, fusion, share, threads, image);
  return image;
}

}  // namespace gridslam::quality
