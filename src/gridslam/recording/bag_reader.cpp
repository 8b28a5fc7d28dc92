#include "gridslam/recording/bag_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include <spdlog/spdlog.h>

#include "gridslam/geometry/pose2.hpp"
#include "gridslam/io/timestamp_repair.hpp"
#include "gridslam/recording/odometry_interpolation.hpp"

namespace gridslam::recording {
namespace {

namespace fs = std::filesystem;
using internal::BagTopic;

std::string StripSlash(const std::string& frame) {
  return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame;
}

bool StartsWith(std::span<const std::uint8_t> bytes, std::string_view magic) {
  return bytes.size() >= magic.size() &&
         std::equal(magic.begin(), magic.end(), reinterpret_cast<const char*>(bytes.data()));
}

// Decodes each message of the topics gridslam reads into `bag`.
class Collector {
 public:
  Collector(BagContents* bag, bool lenient) : bag_(bag), lenient_(lenient) {}

  Status operator()(std::size_t index, std::int64_t log_ns, std::span<const std::uint8_t> data) {
    const BagTopic& topic = bag_->topics[index];
    ++sequence_;
    if (first_) {
      bag_->first_log_ns = bag_->last_log_ns = log_ns;
      first_ = false;
    }
    bag_->first_log_ns = std::min(bag_->first_log_ns, log_ns);
    bag_->last_log_ns = std::max(bag_->last_log_ns, log_ns);
    Status s = Status::Ok();
    switch (KindOfType(topic.type)) {
      case MessageKind::kLaserScan: {
        auto m = DecodeLaserScan(data, topic.encoding);
        if (m.ok()) {
          if (m.value().stamp_ns == 0) {
            m.value().stamp_ns = log_ns;
          }
          m.value().sequence = sequence_;
          bag_->scans[topic.topic].push_back(std::move(m).value());
        } else {
          s = m.error();
        }
        break;
      }
      case MessageKind::kOdometry: {
        auto m = DecodeOdometry(data, topic.encoding);
        if (m.ok()) {
          if (m.value().stamp_ns == 0) {
            m.value().stamp_ns = log_ns;
          }
          m.value().sequence = sequence_;
          bag_->odometry[topic.topic].push_back(std::move(m).value());
        } else {
          s = m.error();
        }
        break;
      }
      case MessageKind::kTf: {
        auto m = DecodeTfMessage(data, topic.encoding);
        if (m.ok()) {
          auto& out = topic.topic == "/tf_static" || topic.topic == "tf_static" ? bag_->tf_static
                                                                                : bag_->tf;
          for (TransformMessage& t : m.value()) {
            t.parent = StripSlash(t.parent);
            t.child = StripSlash(t.child);
            t.sequence = sequence_;
            out.push_back(std::move(t));
          }
        } else {
          s = m.error();
        }
        break;
      }
      case MessageKind::kOther:
        break;
    }
    if (!s.ok()) {
      if (lenient_) {
        ++bag_->skipped_malformed;
        return Status::Ok();
      }
      return InvalidInput("message " + std::to_string(topic.count) + " of " + topic.topic + " (" +
                          topic.type + "): " + s.error().message);
    }
    return Status::Ok();
  }

 private:
  BagContents* bag_;
  bool lenient_;
  bool first_ = true;
  std::uint64_t sequence_ = 0;
};

Result<std::vector<std::uint8_t>> ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return NotFound("cannot open", path);
  }
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  return bytes;
}

Error WithPath(const Error& e, const std::string& path) {
  Error out = e;
  if (out.file.empty()) {
    out.file = path;
  }
  return out;
}

// Fixed transforms child -> (parent, T_parent_child), the latest value of each pair.
using Tree = std::map<std::string, std::pair<std::string, Pose2>>;

// T_ancestor_descendant through the tree, if `ancestor` is on descendant's path to the root.
std::optional<Pose2> Chain(const Tree& tree, const std::string& ancestor,
                           const std::string& descendant) {
  Pose2 T = Pose2::Identity();
  std::string frame = descendant;
  for (int depth = 0; depth < 64; ++depth) {
    if (frame == ancestor) {
      return T;
    }
    auto it = tree.find(frame);
    if (it == tree.end()) {
      return std::nullopt;
    }
    T = it->second.second * T;
    frame = it->second.first;
  }
  return std::nullopt;  // a cycle
}

// Repairs the scan times and the odometry sample stamps in place; returns how many changed.
long RepairStamps(const std::vector<const ScanMessage*>& scans,
                  std::vector<std::int64_t>* scan_time, std::vector<OdometrySample>* samples) {
  // (sequence, scan index or -1 - sample index) in storage order.
  std::vector<std::pair<std::uint64_t, long>> stream;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    stream.emplace_back(scans[i]->sequence, static_cast<long>(i));
  }
  for (std::size_t i = 0; i < samples->size(); ++i) {
    stream.emplace_back((*samples)[i].sequence, -1 - static_cast<long>(i));
  }
  std::sort(stream.begin(), stream.end());
  io::TimestampRepairer repairer;
  long repaired = 0;
  const auto apply = [&](std::uint64_t id, Time t) {
    const long who = stream[id].second;
    std::int64_t& stamp = who >= 0 ? (*scan_time)[static_cast<std::size_t>(who)]
                                   : (*samples)[static_cast<std::size_t>(-1 - who)].stamp_ns;
    const std::int64_t value = t.time_since_epoch().count();
    repaired += value != stamp ? 1 : 0;
    stamp = value;
  };
  for (std::size_t id = 0; id < stream.size(); ++id) {
    const long who = stream[id].second;
    const std::int64_t stamp = who >= 0 ? (*scan_time)[static_cast<std::size_t>(who)]
                                        : (*samples)[static_cast<std::size_t>(-1 - who)].stamp_ns;
    const Time printed{Duration(stamp)};
    repairer.Push(id, FormatSeconds(printed, 6), printed);
    while (auto r = repairer.Pop()) {
      apply(r->first, r->second);
    }
  }
  repairer.Flush();
  while (auto r = repairer.Pop()) {
    apply(r->first, r->second);
  }
  return repaired;
}

Error Ambiguous(const std::string& what, const BagContents& bag) {
  return InvalidInput(what + "; the bag's topics:\n" + ListTopics(bag));
}

}  // namespace

const char* BagFormatName(BagFormat format) {
  switch (format) {
    case BagFormat::kRos1:
      return "ROS 1 bag v2.0";
    case BagFormat::kMcap:
      return "MCAP";
    case BagFormat::kRosbag2Sqlite:
      return "rosbag2 sqlite3";
  }
  return "?";
}

Result<BagContents> LoadBagBytes(std::span<const std::uint8_t> bytes, bool lenient) {
  BagContents bag;
  Collector collector(&bag, lenient);
  const internal::MessageSink sink = [&collector](std::size_t i, std::int64_t t,
                                                  std::span<const std::uint8_t> d) {
    return collector(i, t, d);
  };
  Status s = Status::Ok();
  if (StartsWith(bytes, internal::kRos1Magic)) {
    bag.format = BagFormat::kRos1;
    s = internal::ReadRos1Bag(bytes, &bag.topics, sink);
  } else if (StartsWith(bytes, internal::kMcapMagic)) {
    bag.format = BagFormat::kMcap;
    s = internal::ReadMcap(bytes, &bag.topics, sink);
  } else if (StartsWith(bytes, "#ROSBAG V")) {
    return InvalidInput("unsupported ROS bag version (only v2.0 is read)");
  } else {
    return InvalidInput("not a ROS 1 bag or MCAP file (wrong magic)");
  }
  if (!s.ok()) {
    return s.error();
  }
  return bag;
}

Result<BagContents> LoadBag(const std::string& path, bool lenient) {
  std::error_code ec;
  std::vector<std::string> db3;
  std::string file = path;
  if (fs::is_directory(path, ec)) {
    std::vector<std::string> mcap;
    for (const auto& entry : fs::directory_iterator(path, ec)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".db3") {
        db3.push_back(entry.path().string());
      } else if (ext == ".mcap") {
        mcap.push_back(entry.path().string());
      }
    }
    std::sort(db3.begin(), db3.end());
    if (db3.empty() && mcap.size() == 1) {
      file = mcap.front();
    } else if (db3.empty()) {
      return InvalidInput("folder holds no rosbag2 .db3 (or single .mcap) file", path);
    }
  } else {
    std::ifstream in(path, std::ios::binary);
    char head[16] = {};
    in.read(head, sizeof(head));
    if (in.gcount() == 16 &&
        std::string_view(head, 16) == std::string_view("SQLite format 3\0", 16)) {
      db3.push_back(path);
    }
  }
  if (!db3.empty()) {
    BagContents bag;
    bag.format = BagFormat::kRosbag2Sqlite;
    Collector collector(&bag, lenient);
    const internal::MessageSink sink = [&collector](std::size_t i, std::int64_t t,
                                                    std::span<const std::uint8_t> d) {
      return collector(i, t, d);
    };
    if (Status s = internal::ReadRosbag2Sqlite(db3, &bag.topics, sink); !s.ok()) {
      return WithPath(s.error(), path);
    }
    return bag;
  }
  auto bytes = ReadFileBytes(file);
  if (!bytes.ok()) {
    return bytes.error();
  }
  auto bag = LoadBagBytes(bytes.value(), lenient);
  if (!bag.ok()) {
    return WithPath(bag.error(), file);
  }
  return bag;
}

std::string ListTopics(const BagContents& bag) {
  std::ostringstream out;
  for (const BagTopic& t : bag.topics) {
    out << "  " << t.topic << "  " << t.type << "  " << t.count << " messages\n";
  }
  if (bag.topics.empty()) {
    out << "  (none)\n";
  }
  return out.str();
}

Result<std::vector<Frame>> AssembleBagFrames(const BagContents& bag, const BagOptions& options,
                                             double max_usable_range, BagAssembly* assembly,
                                             bool repair_timestamps) {
  BagAssembly local;
  BagAssembly& a = assembly != nullptr ? *assembly : local;
  a = BagAssembly{};
  // Scans.
  std::vector<std::string> scan_topics;
  for (const BagTopic& t : bag.topics) {
    if (KindOfType(t.type) == MessageKind::kLaserScan) {
      scan_topics.push_back(t.topic);
    }
  }
  if (!options.scan_topic.empty()) {
    if (std::find(scan_topics.begin(), scan_topics.end(), options.scan_topic) ==
        scan_topics.end()) {
      return Ambiguous("no sensor_msgs/LaserScan topic '" + options.scan_topic + "'", bag);
    }
    a.scan_topic = options.scan_topic;
  } else if (scan_topics.size() == 1) {
    a.scan_topic = scan_topics.front();
  } else if (scan_topics.empty()) {
    return Ambiguous("the bag has no sensor_msgs/LaserScan topic", bag);
  } else {
    return Ambiguous("the bag has several LaserScan topics: choose one with --scan-topic", bag);
  }
  auto scans_it = bag.scans.find(a.scan_topic);
  if (scans_it == bag.scans.end() || scans_it->second.empty()) {
    return Ambiguous("topic " + a.scan_topic + " has no messages", bag);
  }
  std::vector<const ScanMessage*> scans;
  for (const ScanMessage& m : scans_it->second) {
    scans.push_back(&m);
  }
  a.laser_frame = StripSlash(scans.front()->frame_id);

  // Odometry source.
  std::vector<std::string> odom_topics;
  for (const BagTopic& t : bag.topics) {
    if (KindOfType(t.type) == MessageKind::kOdometry && t.count > 0) {
      odom_topics.push_back(t.topic);
    }
  }
  const bool tf_requested = !options.odom_frame.empty() || !options.base_frame.empty();
  std::string odom_topic = options.odom_topic;
  if (!odom_topic.empty()) {
    if (!bag.odometry.contains(odom_topic)) {
      return Ambiguous("no nav_msgs/Odometry topic '" + odom_topic + "'", bag);
    }
  } else if (!tf_requested && odom_topics.size() == 1) {
    odom_topic = odom_topics.front();
  } else if (!tf_requested && odom_topics.size() > 1) {
    return Ambiguous(
        "the bag has several Odometry topics: choose one with --odom-topic (or TF with "
        "--odom-frame/--base-frame)",
        bag);
  }
  std::vector<OdometrySample> samples;
  std::string base_frame = StripSlash(options.base_frame);
  if (!odom_topic.empty()) {
    const auto& msgs = bag.odometry.at(odom_topic);
    for (const OdometryMessage& m : msgs) {
      samples.push_back({m.stamp_ns, m.T_odom_base, m.sequence});
    }
    if (base_frame.empty() && !msgs.empty()) {
      base_frame = StripSlash(msgs.front().child_frame_id);
    }
    a.odometry_source = odom_topic;
  }
  const std::string odom_frame =
      options.odom_frame.empty() ? "odom" : StripSlash(options.odom_frame);
  if (base_frame.empty()) {
    base_frame = "base_link";
  }
  // Fixed transforms: /tf_static, and /tf pairs other than the odometry's dynamic ones.
  Tree tree;
  for (const TransformMessage& t : bag.tf_static) {
    tree[t.child] = {t.parent, t.T_parent_child};
  }
  std::map<std::string, std::vector<OdometrySample>> dynamic;  // odom_frame -> child, by child
  for (const TransformMessage& t : bag.tf) {
    if (t.parent == odom_frame) {
      dynamic[t.child].push_back({t.stamp_ns, t.T_parent_child, t.sequence});
    } else if (!tree.contains(t.child)) {
      tree[t.child] = {t.parent, t.T_parent_child};
    }
  }
  if (odom_topic.empty()) {
    // TF odometry: odom_frame -> base_frame, or odom_frame -> X with a fixed chain X -> base.
    for (auto& [child, list] : dynamic) {
      const std::optional<Pose2> T_child_base = Chain(tree, child, base_frame);
      if (!T_child_base) {
        continue;
      }
      for (const OdometrySample& s : list) {
        samples.push_back({s.stamp_ns, s.pose * *T_child_base, s.sequence});
      }
      a.odometry_source = "tf " + odom_frame + "->" + child +
                          (child != base_frame ? "->" + base_frame : std::string());
      break;
    }
    if (samples.empty() && tf_requested) {
      return Ambiguous("no TF odometry " + odom_frame + " -> " + base_frame + " in /tf", bag);
    }
  }
  // Timestamp repair (io/timestamp_repair.hpp) over the scans and odometry in storage order:
  // bags converted from CARMEN logs keep their printed stamps, intel's unpadded ones included.
  std::vector<std::int64_t> scan_time(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    scan_time[i] = scans[i]->stamp_ns;
  }
  if (repair_timestamps) {
    a.repaired_timestamps = RepairStamps(scans, &scan_time, &samples);
  }
  std::stable_sort(
      samples.begin(), samples.end(),
      [](const OdometrySample& x, const OdometrySample& y) { return x.stamp_ns < y.stamp_ns; });
  a.odometry_samples = static_cast<long>(samples.size());
  if (samples.empty()) {
    a.odometry_source = "none";
  }
  a.base_frame = base_frame;

  // Mounting.
  Pose2 T_base_laser = Pose2::Identity();
  if (a.laser_frame != base_frame) {
    if (auto T = Chain(tree, base_frame, a.laser_frame)) {
      T_base_laser = *T;
      a.mounting_from_tf = true;
    } else if (!samples.empty()) {  // without odometry the robot frame is the laser's
      spdlog::warn(
          "no transform chain {} -> {} in /tf_static or /tf: laser assumed at the robot "
          "centre",
          base_frame, a.laser_frame);
    }
  } else {
    a.mounting_from_tf = true;
  }

  std::vector<Frame> frames;
  frames.reserve(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const ScanMessage* m = scans[i];
    Frame f;
    f.time = Time(Duration(m->stamp_ns));
    f.corrected_time = Time(Duration(scan_time[i]));
    f.scan = m->scan;
    f.scan.range_max = std::min(f.scan.range_max, max_usable_range);
    f.T_base_laser = T_base_laser;
    f.source_line = static_cast<long>(i) + 1;
    if (samples.empty()) {
      f.has_odometry = false;
      f.T_odom_base = Pose2::Identity();
    } else {
      bool clamped = false;
      f.T_odom_base = InterpolateOdometry(samples, scan_time[i], &clamped);
      a.scans_outside_odometry += clamped ? 1 : 0;
    }
    frames.push_back(std::move(f));
  }
  return frames;
}

Result<std::size_t> DecodeBagForFuzzing(std::span<const std::uint8_t> bytes) {
  auto bag = LoadBagBytes(bytes, false);
  if (!bag.ok()) {
    return bag.error();
  }
  auto frames = AssembleBagFrames(bag.value(), BagOptions{}, 80.0, nullptr);
  if (!frames.ok()) {
    return frames.error();
  }
  return frames.value().size();
}

}  // namespace gridslam::recording
