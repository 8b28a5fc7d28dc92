#include "app_image_buffer.hpp"

#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gridslam::app {
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;  // x86-64 and arm64 (4 KiB base pages)

}  // namespace

ImageBuffer::~ImageBuffer() { std::free(data_); }

cv::Mat ImageBuffer::Image(int rows, int cols, int type) {
  const std::size_t needed =
      static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols) * CV_ELEM_SIZE(type);
  if (needed > bytes_) {
    std::free(data_);
    data_ = nullptr;
    bytes_ = 0;
    const std::size_t size = (needed + kHugePage - 1) / kHugePage * kHugePage;
    data_ = std::aligned_alloc(kHugePage, size);
    if (data_ == nullptr) {
      throw std::bad_alloc();
    }
    bytes_ = size;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only a hint: without THP the pages are simply small.
    (void)madvise(data_, size, MADV_HUGEPAGE);
#endif
  }
  return cv::Mat(rows, cols, type, data_);
}

}  // namespace gridslam::app
