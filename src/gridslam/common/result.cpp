#include "gridslam/common/result.hpp"

namespace gridslam {

std::string Error::ToString() const {
  if (file.empty()) {
    return message;
  }
  if (line > 0) {
    return file + ":" + std::to_string(line) + ": " + message;
  }
  return file + ": " + message;
}

}  // namespace gridslam
