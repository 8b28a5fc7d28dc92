#include "gridslam/recording/internal/decompress.hpp"

#include <memory>

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

namespace gridslam::recording::internal {
namespace {

// Refuses absurd sizes before allocating (a corrupt length field must not exhaust memory).
constexpr std::size_t kMaxChunk = std::size_t{1} << 32;

Result<std::vector<std::uint8_t>> Bz2(std::span<const std::uint8_t> in, std::size_t size) {
  std::vector<std::uint8_t> out(size);
  auto out_len = static_cast<unsigned int>(size);
  const int rc =
      BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &out_len,
                                 const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                                 static_cast<unsigned int>(in.size()), 0, 0);
  if (rc != BZ_OK) {
    return InvalidInput("corrupt bz2 chunk (libbz2 error " + std::to_string(rc) + ")");
  }
  if (out_len != size) {
    return InvalidInput("bz2 chunk decompresses to " + std::to_string(out_len) +
                        " bytes, the header says " + std::to_string(size));
  }
  return out;
}

Result<std::vector<std::uint8_t>> Lz4(std::span<const std::uint8_t> in, std::size_t size) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    return RuntimeError("cannot create an LZ4 decompression context");
  }
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw, &LZ4F_freeDecompressionContext);
  std::vector<std::uint8_t> out(size);
  std::size_t in_pos = 0;
  std::size_t out_pos = 0;
  std::size_t hint = 1;
  while (in_pos < in.size() && hint != 0) {
    std::size_t in_n = in.size() - in_pos;
    std::size_t out_n = out.size() - out_pos;
    hint = LZ4F_decompress(ctx.get(), out.data() + out_pos, &out_n, in.data() + in_pos, &in_n,
                           nullptr);
    if (LZ4F_isError(hint)) {
      return InvalidInput(std::string("corrupt lz4 chunk: ") + LZ4F_getErrorName(hint));
    }
    in_pos += in_n;
    out_pos += out_n;
    if (in_n == 0 && out_n == 0) {
      break;  // no progress: the output is full but the frame goes on
    }
  }
  if (hint != 0 || out_pos != size) {
    return InvalidInput("lz4 chunk decompresses to " + std::to_string(out_pos) +
                        " bytes, the header says " + std::to_string(size) +
                        (hint != 0 ? " (frame incomplete)" : ""));
  }
  return out;
}

Result<std::vector<std::uint8_t>> Zstd(std::span<const std::uint8_t> in, std::size_t size) {
  std::vector<std::uint8_t> out(size);
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n)) {
    return InvalidInput(std::string("corrupt zstd chunk: ") + ZSTD_getErrorName(n));
  }
  if (n != size) {
    return InvalidInput("zstd chunk decompresses to " + std::to_string(n) +
                        " bytes, the header says " + std::to_string(size));
  }
  return out;
}

}  // namespace

Result<std::vector<std::uint8_t>> Decompress(std::span<const std::uint8_t> input,
                                             Compression compression,
                                             std::size_t uncompressed_size) {
  if (uncompressed_size > kMaxChunk) {
    return InvalidInput("chunk claims " + std::to_string(uncompressed_size) +
                        " uncompressed bytes (corrupt header)");
  }
  switch (compression) {
    case Compression::kNone:
      return std::vector<std::uint8_t>(input.begin(), input.end());
    case Compression::kBz2:
      return Bz2(input, uncompressed_size);
    case Compression::kLz4Frame:
      return Lz4(input, uncompressed_size);
    case Compression::kZstd:
      return Zstd(input, uncompressed_size);
  }
  return RuntimeError("unknown compression");
}

}  // namespace gridslam::recording::internal
