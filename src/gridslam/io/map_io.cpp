#include "gridslam/io/map_io.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/yaml.h>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/options_yaml.hpp"
#include "gridslam/io/png_codec.hpp"

namespace gridslam::io {
namespace {

/// An 8-bit image as stored: row 0 at the top, channels interleaved.
struct RawImage {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<std::uint8_t> data;

  [[nodiscard]] const std::uint8_t* Pixel(int column, int row) const {
    return data.data() + (static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(column)) *
                             static_cast<std::size_t>(channels);
  }
};

bool HasExtension(const std::string& path, const std::string& ext) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return e == ext;
}

/// The largest image read (10^8 pixels, 10000 x 10000): checked from the header, before
/// anything is allocated.
constexpr double kMaxImagePixels = 1e8;

Status CheckImageSize(double width, double height, const std::string& path) {
  if (width * height > kMaxImagePixels) {
    return InvalidInput("image header announces " + std::to_string(static_cast<long long>(width)) +
                            " x " + std::to_string(static_cast<long long>(height)) +
                            " pixels, more than 1e8",
                        path);
  }
  return Status::Ok();
}

/// Checks a PNG's IHDR size before decoding (a 19-byte file claiming a huge size made OpenCV
/// allocate 4.1 GB). Other formats are left to OpenCV (which caps them at 2^30 pixels).
Status CheckPngHeader(const std::string& bytes, const std::string& path) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0) {
    return Status::Ok();  // not a PNG
  }
  if (bytes.size() < 24 || bytes.compare(12, 4, "IHDR") != 0) {
    return InvalidInput("truncated PNG header (no IHDR chunk)", path);
  }
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    }
    return v;
  };
  const std::uint32_t width = be32(16);
  const std::uint32_t height = be32(20);
  if (width == 0 || height == 0) {
    return InvalidInput("PNG header announces an empty image", path);
  }
  return CheckImageSize(width, height, path);
}

/// Reads one whitespace-separated PGM header token, skipping '#' comments.
bool NextToken(const std::string& text, std::size_t& pos, std::string& token) {
  while (pos < text.size()) {
    if (text[pos] == '#') {
      while (pos < text.size() && text[pos] != '\n') {
        ++pos;
      }
    } else if (std::isspace(static_cast<unsigned char>(text[pos])) != 0) {
      ++pos;
    } else {
      break;
    }
  }
  const std::size_t start = pos;
  while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos])) == 0) {
    ++pos;
  }
  token = text.substr(start, pos - start);
  return !token.empty();
}

Result<RawImage> ParsePgm(const std::string& text, const std::string& path) {
  std::size_t pos = 0;
  std::string magic;
  std::string tokens[3];
  if (!NextToken(text, pos, magic) || (magic != "P5" && magic != "P2")) {
    return InvalidInput("not a PGM file (P5 or P2)", path);
  }
  long values[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    if (!NextToken(text, pos, tokens[k])) {
      return InvalidInput("truncated PGM header", path);
    }
    char* end = nullptr;
    values[k] = std::strtol(tokens[k].c_str(), &end, 10);
    if (*end != '\0' || values[k] <= 0 || values[k] > 65535) {
      return InvalidInput("bad PGM header value '" + tokens[k] + "'", path);
    }
  }
  RawImage image;
  image.width = static_cast<int>(values[0]);
  image.height = static_cast<int>(values[1]);
  const long maxval = values[2];
  const std::size_t n =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  GRIDSLAM_RETURN_IF_ERROR(
      CheckImageSize(static_cast<double>(values[0]), static_cast<double>(values[1]), path));
  // The header is checked against the data before anything is allocated: a binary pixel takes
  // 1 or 2 bytes, an ASCII one at least 2 (digit and separator).
  const std::size_t min_bytes = magic == "P5" ? n * (maxval < 256 ? 1 : 2) : 2 * n - 1;
  if (text.size() < pos + min_bytes) {
    return InvalidInput("truncated PGM data (the header announces " + std::to_string(values[0]) +
                            " x " + std::to_string(values[1]) + " pixels)",
                        path);
  }
  image.data.resize(n);
  auto scale = [maxval](long v) {
    return static_cast<std::uint8_t>(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
  };
  if (magic == "P5") {
    ++pos;  // the single whitespace after maxval
    const std::size_t bytes = maxval < 256 ? 1 : 2;
    if (text.size() < pos + n * bytes) {
      return InvalidInput("truncated PGM data", path);
    }
    for (std::size_t k = 0; k < n; ++k) {
      long v = static_cast<unsigned char>(text[pos + k * bytes]);
      if (bytes == 2) {
        v = v * 256 + static_cast<unsigned char>(text[pos + k * bytes + 1]);
      }
      image.data[k] = scale(std::min(v, maxval));
    }
  } else {
    std::string token;
    for (std::size_t k = 0; k < n; ++k) {
      if (!NextToken(text, pos, token)) {
        return InvalidInput("truncated PGM data", path);
      }
      char* end = nullptr;
      const long v = std::strtol(token.c_str(), &end, 10);
      if (*end != '\0' || v < 0 || v > maxval) {
        return InvalidInput("bad PGM value '" + token + "'", path);
      }
      image.data[k] = scale(v);
    }
  }
  return image;
}

Result<RawImage> ReadRawImage(const std::string& path) {
  // The error_code overload: a path the system rejects (too long, say) is an error, not a throw.
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return NotFound("cannot open image", path);
  }
  auto text = ReadTextFile(path);
  if (!text.ok()) {
    return text.error();
  }
  if (text.value().size() >= 2 && text.value()[0] == 'P' &&
      (text.value()[1] == '5' || text.value()[1] == '2')) {
    return ParsePgm(text.value(), path);
  }
  GRIDSLAM_RETURN_IF_ERROR(CheckPngHeader(text.value(), path));
  const std::vector<std::uint8_t> bytes(text.value().begin(), text.value().end());
  auto decoded = DecodeImage(bytes, path);
  if (!decoded.ok()) {
    return decoded.error();
  }
  cv::Mat mat = std::move(decoded.value());
  if (mat.depth() == CV_16U) {
    mat.convertTo(mat, CV_8U, 1.0 / 257.0);
  } else if (mat.depth() != CV_8U) {
    return InvalidInput("unsupported image depth (8 or 16 bit expected)", path);
  }
  RawImage image;
  image.width = mat.cols;
  image.height = mat.rows;
  image.channels = mat.channels();
  image.data.resize(mat.total() * mat.elemSize());
  for (int r = 0; r < mat.rows; ++r) {
    const auto row_bytes = static_cast<std::size_t>(mat.cols) * mat.elemSize();
    std::copy(mat.ptr<std::uint8_t>(r), mat.ptr<std::uint8_t>(r) + row_bytes,
              image.data.begin() + static_cast<long>(static_cast<std::size_t>(r) * row_bytes));
  }
  return image;
}

/// Top row first, as stored in image files.
std::vector<std::uint8_t> FlipRows(const std::vector<std::uint8_t>& cells, int width, int height) {
  std::vector<std::uint8_t> out(cells.size());
  const auto w = static_cast<std::size_t>(width);
  for (int j = 0; j < height; ++j) {
    const auto src = static_cast<std::size_t>(height - 1 - j) * w;
    std::copy(cells.begin() + static_cast<long>(src), cells.begin() + static_cast<long>(src + w),
              out.begin() + static_cast<long>(static_cast<std::size_t>(j) * w));
  }
  return out;
}

Status WriteGrayRows(const std::string& path, const std::vector<std::uint8_t>& rows, int width,
                     int height, double resolution) {
  if (HasExtension(path, ".pgm")) {
    char header[128];
    std::snprintf(header, sizeof(header), "P5\n# CREATOR: gridslam %.3f m/pix\n%d %d\n255\n",
                  resolution, width, height);
    std::string contents(header);
    contents.append(rows.begin(), rows.end());
    return WriteFileAtomically(path, contents);
  }
  if (!HasExtension(path, ".png")) {
    return InvalidInput("cannot write an image of this type (.pgm or .png)", path);
  }
  const cv::Mat mat(height, width, CV_8UC1, const_cast<std::uint8_t*>(rows.data()));
  return WritePng(path, mat);
}

}  // namespace

std::uint8_t TrinaryPixel(signed char occupancy) {
  if (occupancy >= 0 && occupancy <= 25) {
    return 254;
  }
  if (occupancy >= 65) {
    return 0;
  }
  return 205;
}

Status WriteMapImage(const std::string& path, const OccupancyImage& map) {
  if (HasExtension(path, ".pgm")) {
    // Row by row into the file, rows flipped (PGM row 0 is the top): a map may hold tens of
    // millions of cells, and no copy of it is made.
    char header[128];
    std::snprintf(header, sizeof(header), "P5\n# CREATOR: gridslam %.3f m/pix\n%d %d\n255\n",
                  map.Limits().Resolution(), map.Width(), map.Height());
    return WriteFileAtomically(path, [&](std::FILE* f) {
      const auto w = static_cast<std::size_t>(map.Width());
      std::vector<char> row(w);
      bool ok = std::fputs(header, f) >= 0;
      for (int j = map.Height() - 1; ok && j >= 0; --j) {
        const signed char* src = &map.Cells()[static_cast<std::size_t>(j) * w];
        for (std::size_t i = 0; i < w; ++i) {
          row[i] = static_cast<char>(TrinaryPixel(src[i]));
        }
        ok = std::fwrite(row.data(), 1, w, f) == w;
      }
      return ok;
    });
  }
  std::vector<std::uint8_t> cells(map.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    cells[k] = TrinaryPixel(map.Cells()[k]);
  }
  return WriteGrayRows(path, FlipRows(cells, map.Width(), map.Height()), map.Width(), map.Height(),
                       map.Limits().Resolution());
}

Status WriteGrayImage(const std::string& path, const Grid2D<std::uint8_t>& image) {
  return WriteGrayRows(path, FlipRows(image.Cells(), image.Width(), image.Height()), image.Width(),
                       image.Height(), image.Limits().Resolution());
}

Status WriteMap(const std::string& yaml_path, const std::string& image_name,
                const OccupancyImage& map) {
  const std::filesystem::path folder = std::filesystem::path(yaml_path).parent_path();
  GRIDSLAM_RETURN_IF_ERROR(WriteMapImage((folder / image_name).string(), map));
  char yaml[512];
  std::snprintf(yaml, sizeof(yaml),
                "image: %s\nmode: trinary\nresolution: %f\norigin: [%f, %f, %f]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n\n",
                image_name.c_str(), map.Limits().Resolution(), map.Limits().Origin().x(),
                map.Limits().Origin().y(), 0.0);
  return WriteFileAtomically(yaml_path, yaml);
}

Status WriteMapPicture(const std::string& path, const OccupancyImage& map,
                       const std::vector<std::vector<Eigen::Vector2d>>& paths) {
  const int width = map.Width();
  const int height = map.Height();
  cv::Mat image(height, width, CV_8UC3);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const std::uint8_t v = TrinaryPixel(map(i, j));
      image.at<cv::Vec3b>(height - 1 - j, i) = cv::Vec3b(v, v, v);
    }
  }
  // BGR: red, blue, green, orange, purple, teal.
  const cv::Scalar colours[] = {{30, 30, 220}, {220, 90, 20},  {40, 160, 40},
                                {0, 140, 255}, {160, 40, 160}, {160, 160, 0}};
  const double res = map.Limits().Resolution();
  const Eigen::Vector2d origin = map.Limits().Origin();
  auto pixel = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d c = (p - origin) / res;
    return cv::Point(static_cast<int>(std::floor(c.x())),
                     height - 1 - static_cast<int>(std::floor(c.y())));
  };
  const int thickness = std::max(1, static_cast<int>(std::lround(0.1 / res)));
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const cv::Scalar& colour = colours[k % 6];
    const auto& points = paths[k];
    for (std::size_t i = 1; i < points.size(); ++i) {
      cv::line(image, pixel(points[i - 1]), pixel(points[i]), colour, thickness, cv::LINE_8);
    }
    if (!points.empty()) {
      cv::circle(image, pixel(points.front()), std::max(3, static_cast<int>(0.4 / res)), colour,
                 cv::FILLED, cv::LINE_8);
    }
  }
  if (!HasExtension(path, ".png")) {
    return InvalidInput("cannot write a picture of this type (.png)", path);
  }
  return WritePng(path, image);
}

Result<Grid2D<std::uint8_t>> ReadGrayImage(const std::string& path, double resolution,
                                           const Eigen::Vector2d& origin) {
  if (!(resolution > 0.0)) {
    return InvalidInput("image resolution must be > 0", path);
  }
  auto raw = ReadRawImage(path);
  if (!raw.ok()) {
    return raw.error();
  }
  const RawImage& image = raw.value();
  const bool alpha = image.channels == 2 || image.channels == 4;
  const int colours = alpha ? image.channels - 1 : image.channels;
  Grid2D<std::uint8_t> grid(MapLimits(resolution, origin, image.width, image.height), 0);
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const std::uint8_t* p = image.Pixel(col, row);
      int sum = 0;
      for (int c = 0; c < colours; ++c) {
        sum += p[c];
      }
      grid(col, image.height - 1 - row) = static_cast<std::uint8_t>((sum + colours / 2) / colours);
    }
  }
  return grid;
}

Result<OccupancyImage> ReadMap(const std::string& yaml_path) {
  auto text = ReadTextFile(yaml_path);
  if (!text.ok()) {
    return text.error();
  }
  std::string image_name;
  std::string mode = "trinary";
  double resolution = 0.0;
  std::vector<double> origin;
  int negate = 0;
  double occupied_thresh = 0.0;
  double free_thresh = 0.0;
  try {
    const YAML::Node root = YAML::Load(text.value());
    for (const char* key :
         {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"}) {
      if (!root[key]) {
        return InvalidInput(std::string("map YAML lacks '") + key + "'", yaml_path);
      }
    }
    image_name = root["image"].as<std::string>();
    resolution = root["resolution"].as<double>();
    origin = root["origin"].as<std::vector<double>>();
    negate = root["negate"].as<int>();
    occupied_thresh = root["occupied_thresh"].as<double>();
    free_thresh = root["free_thresh"].as<double>();
    if (root["mode"]) {
      mode = root["mode"].as<std::string>();
    }
  } catch (const YAML::Exception& e) {
    return InvalidInput("bad map YAML: " + e.msg, yaml_path, e.mark.line + 1);
  }
  if (!(resolution > 0.0) || origin.size() != 3 || (negate != 0 && negate != 1) ||
      (mode != "trinary" && mode != "scale" && mode != "raw")) {
    return InvalidInput(
        "map YAML needs resolution > 0, origin [x, y, yaw], negate 0 or 1 and "
        "mode trinary, scale or raw",
        yaml_path);
  }
  if (origin[2] != 0.0) {
    return InvalidInput("rotated map origins (yaw != 0) are not supported", yaml_path);
  }
  std::filesystem::path image_path(image_name);
  if (image_path.is_relative()) {
    image_path = std::filesystem::path(yaml_path).parent_path() / image_path;
  }
  auto raw = ReadRawImage(image_path.string());
  if (!raw.ok()) {
    return raw.error();
  }
  const RawImage& image = raw.value();
  const bool has_alpha = image.channels == 2 || image.channels == 4;
  // map_server (ROS 1 image_loader.cpp): alpha is averaged in trinary mode.
  const int averaged = (mode == "trinary" || !has_alpha) ? image.channels : image.channels - 1;
  OccupancyImage map(MapLimits(resolution, {origin[0], origin[1]}, image.width, image.height),
                     kUnknownCell);
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const std::uint8_t* p = image.Pixel(col, row);
      double sum = 0.0;
      for (int c = 0; c < averaged; ++c) {
        sum += p[c];
      }
      double colour = sum / averaged;
      const int alpha = has_alpha ? p[image.channels - 1] : 255;
      if (negate != 0) {
        colour = 255.0 - colour;
      }
      int value = kUnknownCell;
      const double occ = (255.0 - colour) / 255.0;
      if (mode == "raw") {
        value = static_cast<int>(colour);
      } else if (occ > occupied_thresh) {
        value = kOccupiedCell;
      } else if (occ < free_thresh) {
        value = kFreeCell;
      } else if (mode == "scale" && alpha == 255) {
        value =
            static_cast<int>(1.0 + 98.0 * (occ - free_thresh) / (occupied_thresh - free_thresh));
      }
      map(col, image.height - 1 - row) = static_cast<signed char>(value);
    }
  }
  return map;
}

}  // namespace gridslam::io
