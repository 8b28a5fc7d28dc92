// PNG images without OpenCV's image codecs at start-up (issue 19, docs/speed.md, round 23).
//
// Linking libopencv_imgcodecs loads Debian's whole codec tree with the program (GDAL, GDCM and
// 140 shared libraries in all): 0.13 s of dynamic linking at every start of every process,
// whether it touches an image or not. gridslam writes PNG pictures and maps and reads PNG floor
// plans and map_server maps, so:
//  - writing is EncodePng: 8-bit grey, BGR or BGRA rows, every row with the "Sub" filter, zlib
//    at its fastest setting with run-length matching (the settings OpenCV's own writer uses by
//    default), the image data in IDAT chunks of at most 8 MiB;
//  - reading is DecodeImage: OpenCV's decoder (cv::imdecode, every PNG kind it reads), from
//    libopencv_imgcodecs loaded on first use only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gridslam/common/result.hpp"

namespace gridslam::io {

/// The PNG file of `image`: CV_8UC1 (grey), CV_8UC3 (B, G, R) or CV_8UC4 (B, G, R, A), any row
/// stride; not empty. InvalidInput for other types. Images of more than 8 MB are compressed in
/// up to `threads` bands of rows at once; the pixels decoded are the same for any `threads`.
Result<std::string> EncodePng(const cv::Mat& image, int threads = 1);

/// EncodePng written atomically to `path` (io::WriteFileAtomically).
Status WritePng(const std::string& path, const cv::Mat& image, int threads = 1);

/// Decodes an image file's bytes as cv::imdecode(bytes, cv::IMREAD_UNCHANGED) does; `path` names
/// the file in errors. InvalidInput when the bytes do not decode, RuntimeError when OpenCV's codec
/// library cannot be loaded.
Result<cv::Mat> DecodeImage(const std::vector<std::uint8_t>& bytes, const std::string& path);

}  // namespace gridslam::io
