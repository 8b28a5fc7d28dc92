// One pixel buffer that a run's large output pictures are drawn in, one after another (issue 19):
// map_quality.png, map_graph.png and map.png of a large map are 50-140 MB each, and every page of
// a fresh allocation costs a page fault on its first touch. Reused, the buffer is touched once;
// it also asks the kernel for transparent huge pages (madvise), which cut the faults of that one
// touch 512-fold where the system allows them (THP "madvise" or "always").
#pragma once

#include <cstddef>

#include <opencv2/core/mat.hpp>

namespace gridslam::app {

class ImageBuffer {
 public:
  ImageBuffer() = default;
  ~ImageBuffer();
  ImageBuffer(const ImageBuffer&) = delete;
  ImageBuffer& operator=(const ImageBuffer&) = delete;

  /// A continuous rows x cols image of `type` over the buffer (grown when too small; contents
  /// undefined). It stays valid until the next call or the buffer's end, whichever comes first.
  cv::Mat Image(int rows, int cols, int type);
  /// Bytes held.
  [[nodiscard]] std::size_t Bytes() const { return bytes_; }

 private:
  void* data_ = nullptr;
  std::size_t bytes_ = 0;
};

}  // namespace gridslam::app
