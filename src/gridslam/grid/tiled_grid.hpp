// A grid over a MapLimits rectangle whose cells live in square tiles allocated on first write
// (issue 19): the memory of a global map grows with the area the scans touched, not with the
// bounding box of the trajectory (fr-clinic: 38 % of its 9291 x 5017 box, 72 MB instead of
// 186 MB of floats). Cells of tiles never written read as the grid's fill value. Cell indices,
// limits and values are those of a Grid2D over the same MapLimits, so code that walks the cells
// in the same order computes the same numbers.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "gridslam/grid/grid2d.hpp"

namespace gridslam {

template <typename T>
class TiledGrid {
 public:
  static constexpr int kTileBits = 6;
  static constexpr int kTileSize = 1 << kTileBits;  ///< Cells along a tile's side.
  static constexpr int kTileCells = kTileSize * kTileSize;

  TiledGrid() = default;
  TiledGrid(const MapLimits& limits, T fill)
      : limits_(limits),
        fill_(fill),
        tiles_x_((limits.Width() + kTileSize - 1) >> kTileBits),
        tiles_y_((limits.Height() + kTileSize - 1) >> kTileBits),
        tiles_(static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>(tiles_y_)) {}
  TiledGrid(TiledGrid&&) noexcept = default;
  TiledGrid& operator=(TiledGrid&&) noexcept = default;
  TiledGrid(const TiledGrid& other)
      : limits_(other.limits_),
        fill_(other.fill_),
        tiles_x_(other.tiles_x_),
        tiles_y_(other.tiles_y_),
        tiles_(other.tiles_.size()) {
    for (std::size_t t = 0; t < tiles_.size(); ++t) {
      if (other.tiles_[t] != nullptr) {
        tiles_[t] = std::make_unique<T[]>(kTileCells);
        std::copy(other.tiles_[t].get(), other.tiles_[t].get() + kTileCells, tiles_[t].get());
      }
    }
  }
  TiledGrid& operator=(const TiledGrid& other) {
    if (this != &other) {
      *this = TiledGrid(other);
    }
    return *this;
  }
  ~TiledGrid() = default;

  /// The cells of a dense grid (tiles holding only `fill` are not allocated).
  static TiledGrid FromDense(const Grid2D<T>& dense, T fill) {
    TiledGrid grid(dense.Limits(), fill);
    for (int j = 0; j < dense.Height(); ++j) {
      for (int i = 0; i < dense.Width(); ++i) {
        if (dense(i, j) != fill) {
          grid.Mutable(i, j) = dense(i, j);
        }
      }
    }
    return grid;
  }

  [[nodiscard]] const MapLimits& Limits() const { return limits_; }
  [[nodiscard]] int Width() const { return limits_.Width(); }
  [[nodiscard]] int Height() const { return limits_.Height(); }
  [[nodiscard]] T Fill() const { return fill_; }

  /// The value of cell (i, j) (inside the limits).
  [[nodiscard]] T Get(int i, int j) const {
    const T* tile = tiles_[TileIndex(i >> kTileBits, j >> kTileBits)].get();
    return tile == nullptr ? fill_ : tile[InTile(i, j)];
  }
  [[nodiscard]] T Get(const Eigen::Array2i& c) const { return Get(c.x(), c.y()); }
  /// Cell (i, j) for writing; allocates its tile (filled with the fill value) on first use.
  T& Mutable(int i, int j) { return MutableTile(i >> kTileBits, j >> kTileBits)[InTile(i, j)]; }
  T& Mutable(const Eigen::Array2i& c) { return Mutable(c.x(), c.y()); }
  /// The cells of tile (ti, tj) for writing (allocated, filled with the fill value, on first use).
  T* MutableTile(int ti, int tj) {
    std::unique_ptr<T[]>& tile = tiles_[TileIndex(ti, tj)];
    if (tile == nullptr) {
      tile = std::make_unique<T[]>(kTileCells);
      std::fill(tile.get(), tile.get() + kTileCells, fill_);
    }
    return tile.get();
  }
  /// Index of cell (i, j) within its tile.
  [[nodiscard]] static std::size_t InTile(int i, int j) {
    return (static_cast<std::size_t>(j & (kTileSize - 1)) << kTileBits) |
           static_cast<std::size_t>(i & (kTileSize - 1));
  }

  /// Tiles along x and y; tile (ti, tj) covers cells [ti * kTileSize, (ti + 1) * kTileSize) x
  /// [tj * kTileSize, ...), clipped to the limits.
  [[nodiscard]] int TilesX() const { return tiles_x_; }
  [[nodiscard]] int TilesY() const { return tiles_y_; }
  /// The cells of tile (ti, tj), row-major with kTileSize columns; null if never written.
  [[nodiscard]] const T* Tile(int ti, int tj) const { return tiles_[TileIndex(ti, tj)].get(); }
  [[nodiscard]] std::size_t NumAllocatedTiles() const {
    return static_cast<std::size_t>(
        std::count_if(tiles_.begin(), tiles_.end(), [](const auto& t) { return t != nullptr; }));
  }
  /// Heap bytes held.
  [[nodiscard]] std::size_t Bytes() const {
    return NumAllocatedTiles() * kTileCells * sizeof(T) + tiles_.size() * sizeof(tiles_[0]);
  }

  /// Cells [i_begin, i_end) of row j (all inside the grid) into out[0, i_end - i_begin), a
  /// tile's run at a time; the fill where a tile was never written.
  void CopyRow(int j, int i_begin, int i_end, T* out) const {
    const int tj = j >> kTileBits;
    const std::size_t row = static_cast<std::size_t>(j & (kTileSize - 1)) * kTileSize;
    for (int i = i_begin; i < i_end;) {
      const int run = std::min(i_end - i, kTileSize - (i & (kTileSize - 1)));
      const T* tile = Tile(i >> kTileBits, tj);
      T* to = out + (i - i_begin);
      if (tile == nullptr) {
        std::fill(to, to + run, fill_);
      } else {
        const T* from = tile + row + static_cast<std::size_t>(i & (kTileSize - 1));
        std::copy(from, from + run, to);
      }
      i += run;
    }
  }

  /// The same cells as a dense grid (for small maps and tests).
  [[nodiscard]] Grid2D<T> ToDense() const {
    Grid2D<T> dense(limits_, fill_);
    for (int tj = 0; tj < tiles_y_; ++tj) {
      for (int ti = 0; ti < tiles_x_; ++ti) {
        const T* tile = Tile(ti, tj);
        if (tile == nullptr) {
          continue;
        }
        const int i0 = ti * kTileSize;
        const int j0 = tj * kTileSize;
        const int i1 = std::min(limits_.Width(), i0 + kTileSize);
        const int j1 = std::min(limits_.Height(), j0 + kTileSize);
        for (int j = j0; j < j1; ++j) {
          std::copy(tile + (j - j0) * kTileSize, tile + (j - j0) * kTileSize + (i1 - i0),
                    &dense(i0, j));
        }
      }
    }
    return dense;
  }

 private:
  [[nodiscard]] std::size_t TileIndex(int ti, int tj) const {
    return static_cast<std::size_t>(tj) * static_cast<std::size_t>(tiles_x_) +
           static_cast<std::size_t>(ti);
  }
  MapLimits limits_;
  T fill_{};
  int tiles_x_ = 0;
  int tiles_y_ = 0;
  std::vector<std::unique_ptr<T[]>> tiles_;
};

}  // namespace gridslam
