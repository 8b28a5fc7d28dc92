#include <fstream>
#include <sstream>

#include "gridslam/io/options_yaml.hpp"

namespace gridslam::io {

Result<std::string> ReadTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return NotFound("cannot open file", path);
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace gridslam::io
