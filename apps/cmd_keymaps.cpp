// `gridslam keymaps LOG -o DIR`: runs the front end on a CARMEN log and writes every key map for
// people to look at (docs/design.md §1.3-1.4): keymap_NNNN.png (occupied black, free white, unknown
// grey, +y up), keymap_NNNN_distance.png (the exact Euclidean distance transform of the obstacle
// cells, clamped at --distance-clamp metres and scaled to 8 bits) and keymaps.txt (one line per
// key map: id, time, T_odom_key x y theta, number of scans).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include <opencv2/core.hpp>

#include "gridslam/distance_transform/euclidean_distance_transform.hpp"
#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/carmen_reader.hpp"
#include "gridslam/io/png_codec.hpp"
#include "gridslam/keymap/key_map.hpp"
#include "gridslam/recording/recording_reader.hpp"
#include "gridslam/scan_matching/front_end.hpp"

#include "app_output_dir.hpp"
#include "command.hpp"

namespace gridslam::app {
namespace {

struct KeymapsArgs {
  std::string log;
  std::string output;
  double distance_clamp = 2.0;
};

// Row 0 of an image is the top: grid row j goes to image row height - 1 - j.
cv::Mat OccupancyToImage(const OccupancyImage& grid) {
  cv::Mat image(grid.Height(), grid.Width(), CV_8U);
  for (int j = 0; j < grid.Height(); ++j) {
    auto* row = image.ptr<std::uint8_t>(grid.Height() - 1 - j);
    for (int i = 0; i < grid.Width(); ++i) {
      const signed char v = grid(i, j);
      row[i] = v == kUnknownCell ? 128 : (v == kOccupiedCell ? 0 : 255);
    }
  }
  return image;
}

cv::Mat DistanceImage(const Grid2D<std::uint8_t>& obstacles, double clamp) {
  const Grid2D<float> distance = distance_transform::DistanceTransformMetres(obstacles);
  cv::Mat flipped(distance.Height(), distance.Width(), CV_32F);
  for (int j = 0; j < distance.Height(); ++j) {
    auto* row = flipped.ptr<float>(distance.Height() - 1 - j);
    for (int i = 0; i < distance.Width(); ++i) {
      row[i] = distance(i, j);
    }
  }
  return distance_transform::DistanceToImage(flipped, clamp);
}

Status WriteKeyMap(const std::filesystem::path& dir, const keymap::KeyMap& key,
                   const scan_matching::FrontEndOptions& options, double clamp,
                   std::string& index) {
  char name[32];
  std::snprintf(name, sizeof(name), "keymap_%04d", key.id);
  const double occupied = options.local_map.occupied_probability;
  const OccupancyImage occupancy = keymap::ToOccupancyImage(key.log_odds, occupied, 0.5);
  const std::string grid_path = (dir / (std::string(name) + ".png")).string();
  const std::string distance_path = (dir / (std::string(name) + "_distance.png")).string();
  // Encoded in memory and written atomically, so write errors (a full disk) are detected.
  for (const auto& [path, image] :
       {std::pair{grid_path, OccupancyToImage(occupancy)},
        std::pair{distance_path,
                  DistanceImage(keymap::ObstacleMask(key.log_odds, occupied), clamp)}}) {
    GRIDSLAM_RETURN_IF_ERROR(io::WritePng(path, image));
  }
  std::ostringstream line;
  line << key.id << " " << FormatSeconds(key.time) << " " << key.T_odom_key.x() << " "
       << key.T_odom_key.y() << " " << key.T_odom_key.theta() << " " << key.scans.size() << "\n";
  index += line.str();
  return Status::Ok();
}

int RunKeymaps(const KeymapsArgs& args, AppContext& context) {
  scan_matching::FrontEndOptions options = context.options.front_end;
  options.keymap.keep_scans = false;  // only the grids are written
  if (const Status s = options.Validate(); !s.ok()) {
    return ReportError(s.error());
  }
  if (!(args.distance_clamp > 0.0)) {
    return ReportError(InvalidInput("--distance-clamp must be > 0"));
  }
  auto reader = recording::RecordingReader::Open(args.log, context.Recording());
  if (!reader.ok()) {
    return ReportError(reader.error());
  }
  auto output = OutputDir::Begin(args.output);  // staged, committed at the end (issue 17)
  if (!output.ok()) {
    return ReportError(output.error());
  }
  const std::filesystem::path dir(output.value()->path());
  std::string index = "# id time T_odom_key.x T_odom_key.y T_odom_key.theta scans\n";
  scan_matching::FrontEnd front_end(options);
  long scans = 0;
  while (true) {
    auto next = reader.value().Next();
    if (!next.ok()) {
      return ReportError(next.error());
    }
    if (!next.value()) {
      break;
    }
    ++scans;
    scan_matching::FrontEndStep step = front_end.AddFrame(*next.value());
    if (step.key_map) {
      if (const Status s = WriteKeyMap(dir, *step.key_map, options, args.distance_clamp, index);
          !s.ok()) {
        return ReportError(s.error());
      }
    }
  }
  if (auto last = front_end.Finish()) {
    if (const Status s = WriteKeyMap(dir, *last, options, args.distance_clamp, index); !s.ok()) {
      return ReportError(s.error());
    }
  }
  if (scans == 0) {
    return ReportError(io::NoScansError(args.log, reader.value().Stats()));
  }
  if (const Status s = io::WriteFileAtomically((dir / "keymaps.txt").string(), index); !s.ok()) {
    return ReportError(s.error());
  }
  if (const Status s = output.value()->Commit(); !s.ok()) {
    return ReportError(s.error());
  }

  std::fprintf(stderr, "gridslam keymaps: %ld scans, %ld key maps written to %s\n", scans,
               front_end.Stats().key_maps, args.output.c_str());
  return kExitOk;
}

RunFunction SetupKeymaps(CLI::App& sub, AppContext& /*context*/) {
  auto args = std::make_shared<KeymapsArgs>();
  sub.add_option("LOG", args->log,
                 "Recording: CARMEN log (optionally gzip-compressed) or bag (.bag, .mcap, rosbag2)")
      ->required();
  sub.add_option("-o,--output", args->output, "Output folder")->required()->check(OutputFolder());
  sub.add_option("--distance-clamp", args->distance_clamp,
                 "Distances at or beyond this are white in the distance images [m]");
  return [args](AppContext& ctx) { return RunKeymaps(*args, ctx); };
}

GRIDSLAM_REGISTER_COMMAND(CommandSpec{
    "keymaps", "Write the front end's key maps and their distance images as PNG", SetupKeymaps});

}  // namespace
}  // namespace gridslam::app
