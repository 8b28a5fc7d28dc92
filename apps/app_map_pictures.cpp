#include "app_map_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "gridslam/io/png_codec.hpp"

namespace gridslam::app {
namespace {

constexpr int kMarginLeft = 56;    // room for the y tick labels [px]
constexpr int kMarginBottom = 34;  // room for the x tick labels [px]
constexpr int kMarginTop = 8;
constexpr int kMarginRight = 12;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.4;
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kClosureColour(0, 170, 0);   // green
const cv::Scalar kKeyMapColour(150, 150, 0);  // dark cyan

cv::Scalar ToScalar(Bgr c) { return cv::Scalar(c.b, c.g, c.r); }

std::string Metres(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), std::abs(v - std::round(v)) < 1e-6 ? "%.0f" : "%.1f", v);
  return text;
}

/// The map on a white canvas with margins for the axes; `pixel` maps metric map-frame points to
/// canvas pixels.
struct Canvas {
  cv::Mat image;
  MapLimits limits;
  [[nodiscard]] cv::Point Pixel(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d c = (p - limits.Origin()) / limits.Resolution();
    return {kMarginLeft + static_cast<int>(std::floor(c.x())),
            kMarginTop + limits.Height() - 1 - static_cast<int>(std::floor(c.y()))};
  }
};

/// `channels` 1: grey levels (map.png); 3: BGR, for the coloured layers of map_graph.png. Drawn
/// in `pictures`.
Canvas MakeCanvas(const OccupancyImage& map, int channels, ImageBuffer& pictures) {
  const MapLimits& limits = map.Limits();
  Canvas canvas{pictures.Image(kMarginTop + limits.Height() + kMarginBottom,
                               kMarginLeft + limits.Width() + kMarginRight, CV_8UC(channels)),
                limits};
  canvas.image.setTo(cv::Scalar::all(255));
  const auto grey = [](signed char v) -> std::uint8_t {
    return v == kOccupiedCell ? 0 : (v == kFreeCell ? 255 : 205);
  };
  for (int j = 0; j < limits.Height(); ++j) {
    std::uint8_t* row = canvas.image.ptr<std::uint8_t>(kMarginTop + limits.Height() - 1 - j) +
                        kMarginLeft * channels;
    const signed char* cells = &map.Cells()[static_cast<std::size_t>(j) * limits.Width()];
    if (channels == 1) {
      std::transform(cells, cells + limits.Width(), row, grey);
      continue;
    }
    for (int i = 0; i < limits.Width(); ++i) {
      const std::uint8_t g = grey(cells[i]);
      for (int c = 0; c < channels; ++c) {
        row[i * channels + c] = g;
      }
    }
  }
  return canvas;
}

/// Axes in metres of the map frame along the bottom and left edges, and a scale bar.
void DrawAxesAndScale(Canvas& canvas) {
  const MapLimits& l = canvas.limits;
  const double res = l.Resolution();
  const double x0 = l.Origin().x();
  const double y0 = l.Origin().y();
  const double x1 = x0 + l.Width() * res;
  const double y1 = y0 + l.Height() * res;
  const int left = kMarginLeft;
  const int bottom = kMarginTop + l.Height();
  const int right = kMarginLeft + l.Width();
  cv::rectangle(canvas.image, cv::Point(left - 1, kMarginTop - 1), cv::Point(right, bottom), kBlack,
                1);
  const double dx = TickSpacing(x1 - x0);
  for (double x = std::ceil(x0 / dx) * dx; x <= x1; x += dx) {
    const int u = canvas.Pixel({x, y0}).x;
    cv::line(canvas.image, cv::Point(u, bottom), cv::Point(u, bottom + 4), kBlack, 1);
    const std::string text = Metres(x);
    int base = 0;
    const cv::Size size = cv::getTextSize(text, kFont, kFontScale, 1, &base);
    cv::putText(canvas.image, text, cv::Point(u - size.width / 2, bottom + 6 + size.height), kFont,
                kFontScale, kBlack, 1, cv::LINE_AA);
  }
  cv::putText(canvas.image, "x [m]", cv::Point(right - 34, bottom + 30), kFont, kFontScale, kBlack,
              1, cv::LINE_AA);
  const double dy = TickSpacing(y1 - y0);
  for (double y = std::ceil(y0 / dy) * dy; y <= y1; y += dy) {
    const int v = canvas.Pixel({x0, y}).y;
    cv::line(canvas.image, cv::Point(left - 5, v), cv::Point(left - 1, v), kBlack, 1);
    const std::string text = Metres(y);
    int base = 0;
    const cv::Size size = cv::getTextSize(text, kFont, kFontScale, 1, &base);
    cv::putText(canvas.image, text, cv::Point(left - 8 - size.width, v + size.height / 2), kFont,
                kFontScale, kBlack, 1, cv::LINE_AA);
  }
  cv::putText(canvas.image, "y [m]", cv::Point(4, kMarginTop + 10), kFont, kFontScale, kBlack, 1,
              cv::LINE_AA);
  // Scale bar: a round length about a fifth of the width, bottom right inside the map.
  const double bar_m = TickSpacing(0.5 * (x1 - x0));
  const int bar_px = static_cast<int>(std::lround(bar_m / res));
  const cv::Point end(right - 10, bottom - 10);
  const cv::Point start(end.x - bar_px, end.y);
  cv::rectangle(canvas.image, start + cv::Point(-4, -18), end + cv::Point(4, 4),
                cv::Scalar(255, 255, 255), cv::FILLED);
  cv::line(canvas.image, start, end, kBlack, 2);
  cv::line(canvas.image, start + cv::Point(0, -4), start + cv::Point(0, 2), kBlack, 1);
  cv::line(canvas.image, end + cv::Point(0, -4), end + cv::Point(0, 2), kBlack, 1);
  cv::putText(canvas.image, Metres(bar_m) + " m", cv::Point(start.x, end.y - 7), kFont, kFontScale,
              kBlack, 1, cv::LINE_AA);
}

}  // namespace

Bgr RobotColour(std::size_t robot) {
  // Red, blue, orange, purple, brown: distinct from the closures' green and the key maps' cyan.
  static const std::vector<Bgr> kColours = {
      {0, 0, 220}, {220, 60, 0}, {0, 140, 255}, {170, 0, 150}, {30, 70, 140}};
  return kColours[robot % kColours.size()];
}

double TickSpacing(double length_m) {
  if (!(length_m > 0.0)) {
    return 1.0;
  }
  const double raw = length_m / 6.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double step : {1.0, 2.0, 5.0}) {
    if (step * power >= raw) {
      return step * power;
    }
  }
  return 10.0 * power;
}

Status WriteMapPicture(const std::string& path, const OccupancyImage& map, ImageBuffer& pictures,
                       int threads) {
  Canvas canvas =
      MakeCanvas(map, 1, pictures);  // black, white and grey: one channel is a third to encode
  DrawAxesAndScale(canvas);
  return io::WritePng(path, canvas.image, threads);
}

Status WriteGraphPicture(const std::string& path, const OccupancyImage& map,
                         const pipeline::MapperResult& result, int component, ImageBuffer& pictures,
                         int threads) {
  Canvas canvas = MakeCanvas(map, 3, pictures);
  std::vector<std::size_t> robots;
  for (std::size_t r = 0; r < result.trajectories.size(); ++r) {
    if (result.component_of_robot[r] != component) {
      continue;
    }
    robots.push_back(r);
    const auto& trajectory = result.trajectories[r];
    for (std::size_t k = 1; k < trajectory.size(); ++k) {
      cv::line(canvas.image, canvas.Pixel(trajectory[k - 1].T_map_base.translation()),
               canvas.Pixel(trajectory[k].T_map_base.translation()), ToScalar(RobotColour(r)), 1);
    }
  }
  const pose_graph::PoseGraph& graph = result.graph;
  const auto in_component = [&](int id) {
    return result.component_of_robot[static_cast<std::size_t>(
               result.vertex_robot[static_cast<std::size_t>(id)])] == component;
  };
  for (const pipeline::ClosureRecord& c : result.closures) {
    if ((c.outcome == pipeline::ClosureOutcome::kAccepted ||
         c.outcome == pipeline::ClosureOutcome::kJoined) &&
        in_component(c.from)) {
      cv::line(
          canvas.image, canvas.Pixel(graph.vertex(graph.IndexOf(c.from)).T_map_v.translation()),
          canvas.Pixel(graph.vertex(graph.IndexOf(c.to)).T_map_v.translation()), kClosureColour, 1);
    }
  }
  for (const auto& v : graph.vertices()) {
    if (in_component(v.id)) {
      cv::circle(canvas.image, canvas.Pixel(v.T_map_v.translation()), 2, kKeyMapColour, -1);
    }
  }
  DrawAxesAndScale(canvas);
  // Legend, top left inside the map: one line per robot, then key maps and loop closures.
  const int rows = static_cast<int>(robots.size()) + 2;
  const cv::Point corner(kMarginLeft + 6, kMarginTop + 6);
  cv::rectangle(canvas.image, corner, corner + cv::Point(150, 8 + 16 * rows),
                cv::Scalar(255, 255, 255), cv::FILLED);
  cv::rectangle(canvas.image, corner, corner + cv::Point(150, 8 + 16 * rows), kBlack, 1);
  int y = corner.y + 14;
  const auto entry = [&](const std::string& text) {
    cv::putText(canvas.image, text, cv::Point(corner.x + 30, y + 4), kFont, kFontScale, kBlack, 1,
                cv::LINE_AA);
    y += 16;
  };
  for (const std::size_t r : robots) {
    cv::line(canvas.image, cv::Point(corner.x + 6, y), cv::Point(corner.x + 24, y),
             ToScalar(RobotColour(r)), 2);
    entry(robots.size() > 1 || result.trajectories.size() > 1
              ? "robot " + std::to_string(r) + " trajectory"
              : "trajectory");
  }
  cv::circle(canvas.image, cv::Point(corner.x + 15, y), 3, kKeyMapColour, -1);
  entry("key map");
  cv::line(canvas.image, cv::Point(corner.x + 6, y), cv::Point(corner.x + 24, y), kClosureColour,
           2);
  entry("loop closure");
  return io::WritePng(path, canvas.image, threads);
}

}  // namespace gridslam::app
