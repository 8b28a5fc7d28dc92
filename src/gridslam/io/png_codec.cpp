#include "gridslam/io/png_codec.hpp"

#include <algorithm>
#include <array>
#include <cstring>

#include <zlib.h>

#include "gridslam/common/parallel.hpp"
#include "gridslam/io/atomic_file.hpp"

#include <dlfcn.h>

#ifndef GRIDSLAM_OPENCV_IMGCODECS
#define GRIDSLAM_OPENCV_IMGCODECS "libopencv_imgcodecs.so"
#endif

namespace gridslam::io {
namespace {

constexpr std::size_t kMaxChunk = std::size_t{8} << 20U;  // IDAT data per chunk [bytes]
// Image data below which a thread is not worth starting for a band of rows [bytes].
constexpr std::size_t kMinBytesPerBand = std::size_t{4} << 20U;

void AppendU32(std::string& out, std::uint32_t v) {
  const std::array<char, 4> bytes = {static_cast<char>(v >> 24U), static_cast<char>(v >> 16U),
                                     static_cast<char>(v >> 8U), static_cast<char>(v)};
  out.append(bytes.data(), bytes.size());
}

// One chunk: length, type, data, CRC of type and data (PNG spec §5.3).
void AppendChunk(std::string& out, const char* type, const char* data, std::size_t size) {
  AppendU32(out, static_cast<std::uint32_t>(size));
  const std::size_t start = out.size();
  out.append(type, 4);
  out.append(data, size);
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, reinterpret_cast<const Bytef*>(out.data() + start),
              static_cast<uInt>(out.size() - start));
  AppendU32(out, static_cast<std::uint32_t>(crc));
}

// Deflate output of the filtered rows, compressed as the rows come: a zlib stream (header,
// data, Adler-32) or raw deflate data to be joined with others (no header and no check value;
// `last` ends it with the final block, otherwise with a sync flush, which byte-aligns it so that
// the next part's blocks can follow).
class Deflater {
 public:
  explicit Deflater(bool raw) {
    // Level 1 with run-length matching: what OpenCV's PNG writer uses unless told otherwise.
    ok_ = deflateInit2(&stream_, Z_BEST_SPEED, Z_DEFLATED, raw ? -15 : 15, 8, Z_RLE) == Z_OK;
  }
  ~Deflater() { deflateEnd(&stream_); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  [[nodiscard]] bool ok() const { return ok_; }
  bool Add(const std::uint8_t* data, std::size_t size, int flush) {
    stream_.next_in = const_cast<Bytef*>(data);  // zlib's API is not const-correct
    stream_.avail_in = static_cast<uInt>(size);
    int status = Z_OK;
    do {
      stream_.next_out = buffer_.data();
      stream_.avail_out = static_cast<uInt>(buffer_.size());
      status = deflate(&stream_, flush);
      if (status == Z_STREAM_ERROR) {
        return false;
      }
      out_.append(reinterpret_cast<const char*>(buffer_.data()),
                  buffer_.size() - stream_.avail_out);
    } while (stream_.avail_out == 0 || (flush == Z_FINISH && status != Z_STREAM_END));
    return true;
  }
  [[nodiscard]] std::string& Output() { return out_; }

 private:
  z_stream stream_{};
  bool ok_ = false;
  std::vector<Bytef> buffer_ = std::vector<Bytef>(std::size_t{1} << 16U);  // deflate's output
  std::string out_;
};

// Rows [row0, row1) of the image, filtered and deflated: a whole zlib stream when they are all
// of it, else a raw part (see Deflater). `adler` receives the Adler-32 of the filtered bytes.
bool DeflateRows(const cv::Mat& image, int row0, int row1, bool whole, bool last, std::string& out,
                 uLong& adler) {
  const auto width = static_cast<std::size_t>(image.cols);
  const auto channels = static_cast<std::size_t>(image.channels());
  const std::size_t row_bytes = width * channels;
  Deflater deflater(!whole);
  if (!deflater.ok()) {
    return false;
  }
  adler = adler32(0L, Z_NULL, 0);
  // Each row: filter type 1 ("Sub": every byte minus the same byte of the pixel to its left),
  // the pixels in R, G, B(, A) order.
  std::vector<std::uint8_t> pixels(row_bytes);
  std::vector<std::uint8_t> filtered(row_bytes + 1);
  filtered[0] = 1;
  for (int r = row0; r < row1; ++r) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(r);
    if (channels == 1) {
      std::memcpy(pixels.data(), row, row_bytes);
    } else {
      for (std::size_t i = 0; i < row_bytes; i += channels) {
        pixels[i] = row[i + 2];
        pixels[i + 1] = row[i + 1];
        pixels[i + 2] = row[i];
        if (channels == 4) {
          pixels[i + 3] = row[i + 3];
        }
      }
    }
    std::copy(pixels.begin(), pixels.begin() + static_cast<std::ptrdiff_t>(channels),
              filtered.begin() + 1);
    for (std::size_t i = channels; i < row_bytes; ++i) {
      filtered[i + 1] = static_cast<std::uint8_t>(pixels[i] - pixels[i - channels]);
    }
    if (!whole) {
      adler = adler32(adler, filtered.data(), static_cast<uInt>(filtered.size()));
    }
    const bool end = r + 1 == row1;
    const int flush = end ? (last ? Z_FINISH : Z_SYNC_FLUSH) : Z_NO_FLUSH;
    if (!deflater.Add(filtered.data(), filtered.size(), flush)) {
      return false;
    }
  }
  out = std::move(deflater.Output());
  return true;
}

using Imdecode = cv::Mat (*)(const cv::_InputArray&, int);
constexpr int kImreadUnchanged = -1;  // cv::IMREAD_UNCHANGED

struct Decoder {
  Imdecode imdecode = nullptr;
  std::string error;
};

// cv::imdecode from OpenCV's codec library, loaded once, never unloaded.
const Decoder& LoadDecoder() {
  static const Decoder decoder = [] {
    Decoder d;
    void* library = dlopen(GRIDSLAM_OPENCV_IMGCODECS, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
      const char* why = dlerror();
      d.error = std::string("cannot load OpenCV's image codecs (") + GRIDSLAM_OPENCV_IMGCODECS +
                "): " + (why != nullptr ? why : "unknown error");
      return d;
    }
    // cv::imdecode(cv::InputArray, int): the C++ name as the library exports it.
    void* symbol = dlsym(library, "_ZN2cv8imdecodeERKNS_11_InputArrayEi");
    if (symbol == nullptr) {
      d.error = std::string("cv::imdecode not found in ") + GRIDSLAM_OPENCV_IMGCODECS;
      return d;
    }
    d.imdecode = reinterpret_cast<Imdecode>(symbol);
    return d;
  }();
  return decoder;
}

}  // namespace

Result<std::string> EncodePng(const cv::Mat& image, int threads) {
  if (image.empty() || image.depth() != CV_8U ||
      (image.channels() != 1 && image.channels() != 3 && image.channels() != 4) ||
      image.dims != 2) {
    return InvalidInput("PNG: only non-empty 8-bit images of 1, 3 or 4 channels are written");
  }
  const auto channels = static_cast<std::size_t>(image.channels());
  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string header;
  AppendU32(header, static_cast<std::uint32_t>(image.cols));
  AppendU32(header, static_cast<std::uint32_t>(image.rows));
  const char colour_type = channels == 1 ? 0 : (channels == 3 ? 2 : 6);  // grey, RGB, RGBA
  header += {8, colour_type, 0, 0, 0};  // bit depth, colour type, deflate, filters, no interlace
  AppendChunk(out, "IHDR", header.data(), header.size());

  // Large images are deflated in row bands, one per thread, joined as pigz does: a zlib header,
  // the bands' raw data (each but the last ending on a byte boundary), and the Adler-32 of the
  // whole, combined from the bands'. Each band starts without the previous one's history, which
  // costs a few bytes; smaller images are one zlib stream.
  const std::size_t bytes = static_cast<std::size_t>(image.rows) * image.cols * channels;
  const std::size_t parts = bytes < kMinBytesPerBand * 2
                                ? 1
                                : std::min(PartCount(static_cast<std::size_t>(image.rows), threads),
                                           bytes / kMinBytesPerBand);
  std::vector<std::string> data(parts);
  std::vector<uLong> adler(parts, 0);
  std::vector<char> ok(parts, 0);
  const auto rows = static_cast<std::size_t>(image.rows);
  RunParts(rows, parts, [&](std::size_t part, std::size_t begin, std::size_t end) {
    ok[part] = DeflateRows(image, static_cast<int>(begin), static_cast<int>(end), parts == 1,
                           part + 1 == parts, data[part], adler[part])
                   ? 1
                   : 0;
  });
  if (std::find(ok.begin(), ok.end(), 0) != ok.end()) {
    return RuntimeError("PNG: zlib failed");
  }
  std::string stream;
  if (parts == 1) {
    stream = std::move(data[0]);
  } else {
    stream = "\x78\x01";  // zlib header: deflate, 32 KiB window, fastest level (RFC 1950)
    uLong check = adler[0];
    for (std::size_t p = 0; p < parts; ++p) {
      stream += data[p];
      if (p > 0) {
        const std::size_t band_rows = rows * (p + 1) / parts - rows * p / parts;
        const auto band_bytes =
            static_cast<z_off_t>(band_rows * (static_cast<std::size_t>(image.cols) * channels + 1));
        check = adler32_combine(check, adler[p], band_bytes);
      }
    }
    AppendU32(stream, static_cast<std::uint32_t>(check));
  }
  for (std::size_t at = 0; at < stream.size(); at += kMaxChunk) {
    AppendChunk(out, "IDAT", stream.data() + at, std::min(kMaxChunk, stream.size() - at));
  }
  AppendChunk(out, "IEND", "", 0);
  return out;
}

Status WritePng(const std::string& path, const cv::Mat& image, int threads) {
  auto png = EncodePng(image, threads);
  if (!png.ok()) {
    Error error = png.error();
    error.file = path;
    return error;
  }
  return WriteFileAtomically(path, png.value());
}

Result<cv::Mat> DecodeImage(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  const Decoder& decoder = LoadDecoder();
  if (decoder.imdecode == nullptr) {
    return RuntimeError("cannot read image '" + path + "': " + decoder.error);
  }
  cv::Mat mat;
  try {
    mat = decoder.imdecode(bytes, kImreadUnchanged);
  } catch (const cv::Exception& e) {
    return InvalidInput(std::string("cannot decode image: ") + e.what(), path);
  }
  if (mat.empty()) {
    return InvalidInput("cannot decode image", path);
  }
  return mat;
}

}  // namespace gridslam::io
