// Test-only writers of tiny bags (ROS 1 v2.0 and MCAP) and of the three message types in both
// wire formats, so the readers are tested on files built in the test, never on data copies.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <zlib.h>

#include "gridslam/recording/ros_messages.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

namespace gridslam::recording::testing {

using Bytes = std::vector<std::uint8_t>;

template <class T>
void PutRaw(Bytes& out, T value) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}
inline void PutBytes(Bytes& out, const std::string& s) {
  out.insert(out.end(), s.begin(), s.end());
}

// Serializes message fields in ROS 1 or CDR (little endian) layout.
class WireWriter {
 public:
  explicit WireWriter(MessageEncoding e) : e_(e) {
    if (e_ == MessageEncoding::kCdr) {
      out_ = {0x00, 0x01, 0x00, 0x00};
    }
  }
  template <class T>
  void Put(T v) {
    if (e_ == MessageEncoding::kCdr) {
      while ((out_.size() - 4) % sizeof(T) != 0) {
        out_.push_back(0);
      }
    }
    PutRaw(out_, v);
  }
  void String(const std::string& s) {
    const bool cdr = e_ == MessageEncoding::kCdr;
    Put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + (cdr ? 1 : 0)));
    PutBytes(out_, s);
    if (cdr) {
      out_.push_back(0);
    }
  }
  void Header(std::int64_t stamp_ns, const std::string& frame) {
    if (e_ == MessageEncoding::kRos1) {
      Put<std::uint32_t>(7);  // seq
    }
    Put<std::uint32_t>(static_cast<std::uint32_t>(stamp_ns / 1000000000));
    Put<std::uint32_t>(static_cast<std::uint32_t>(stamp_ns % 1000000000));
    String(frame);
  }
  void Pose(double x, double y, double yaw) {
    Put(x);
    Put(y);
    Put(0.0);
    Put(0.0);
    Put(0.0);
    Put(std::sin(yaw / 2));
    Put(std::cos(yaw / 2));
  }
  Bytes Take() { return std::move(out_); }

 private:
  MessageEncoding e_;
  Bytes out_;
};

inline Bytes ScanBytes(MessageEncoding e, std::int64_t stamp, const std::string& frame,
                       float angle_min, float increment, const std::vector<float>& ranges,
                       float range_min = 0.1F, float range_max = 30.0F) {
  WireWriter w(e);
  w.Header(stamp, frame);
  w.Put(angle_min);
  w.Put(angle_min + increment * static_cast<float>(ranges.size() - 1));
  w.Put(increment);
  w.Put(0.0F);
  w.Put(0.1F);
  w.Put(range_min);
  w.Put(range_max);
  w.Put<std::uint32_t>(static_cast<std::uint32_t>(ranges.size()));
  for (float r : ranges) {
    w.Put(r);
  }
  w.Put<std::uint32_t>(0);  // intensities
  return w.Take();
}

inline Bytes OdometryBytes(MessageEncoding e, std::int64_t stamp, double x, double y, double yaw,
                           const std::string& child = "base_link") {
  WireWriter w(e);
  w.Header(stamp, "odom");
  w.String(child);
  w.Pose(x, y, yaw);
  for (int i = 0; i < 36; ++i) {
    w.Put(0.0);
  }
  for (int i = 0; i < 6 + 36; ++i) {
    w.Put(0.0);
  }
  return w.Take();
}

struct TestTransform {
  std::int64_t stamp;
  std::string parent;
  std::string child;
  double x, y, yaw;
};

inline Bytes TfBytes(MessageEncoding e, const std::vector<TestTransform>& transforms) {
  WireWriter w(e);
  w.Put<std::uint32_t>(static_cast<std::uint32_t>(transforms.size()));
  for (const TestTransform& t : transforms) {
    w.Header(t.stamp, t.parent);
    w.String(t.child);
    w.Pose(t.x, t.y, t.yaw);
  }
  return w.Take();
}

struct TestMessage {
  int connection;  ///< Index into the topics.
  std::int64_t time_ns;
  Bytes data;
};
struct TestTopic {
  std::string topic;
  std::string type;
};

// ---- ROS 1 bag v2.0 ----
inline void Ros1Field(Bytes& header, const std::string& name, const Bytes& value) {
  PutRaw<std::uint32_t>(header, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
  PutBytes(header, name + "=");
  header.insert(header.end(), value.begin(), value.end());
}
template <class T>
Bytes Le(T v) {
  Bytes b;
  PutRaw(b, v);
  return b;
}
inline Bytes Str(const std::string& s) { return {s.begin(), s.end()}; }
inline void Ros1Record(Bytes& out, const Bytes& header, const Bytes& data) {
  PutRaw<std::uint32_t>(out, static_cast<std::uint32_t>(header.size()));
  out.insert(out.end(), header.begin(), header.end());
  PutRaw<std::uint32_t>(out, static_cast<std::uint32_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
}
inline void Ros1Connection(Bytes& out, int id, const TestTopic& t) {
  Bytes h;
  Ros1Field(h, "op", {0x07});
  Ros1Field(h, "conn", Le<std::uint32_t>(static_cast<std::uint32_t>(id)));
  Ros1Field(h, "topic", Str(t.topic));
  Bytes d;
  Ros1Field(d, "topic", Str(t.topic));
  Ros1Field(d, "type", Str(t.type));
  Ros1Field(d, "md5sum", Str("0"));
  Ros1Field(d, "message_definition", Str(""));
  Ros1Record(out, h, d);
}

inline Bytes Compress(const Bytes& raw, const std::string& how) {
  if (how == "bz2") {
    Bytes out(raw.size() + raw.size() / 100 + 700);
    auto n = static_cast<unsigned>(out.size());
    BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out.data()), &n,
                             const_cast<char*>(reinterpret_cast<const char*>(raw.data())),
                             static_cast<unsigned>(raw.size()), 9, 0, 0);
    out.resize(n);
    return out;
  }
  if (how == "lz4") {
    Bytes out(LZ4F_compressFrameBound(raw.size(), nullptr));
    out.resize(LZ4F_compressFrame(out.data(), out.size(), raw.data(), raw.size(), nullptr));
    return out;
  }
  if (how == "zstd") {
    Bytes out(ZSTD_compressBound(raw.size()));
    out.resize(ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 3));
    return out;
  }
  return raw;
}

/// compression: "none", "bz2" or "lz4". indexed = false writes index_pos 0 (an unclosed bag).
inline Bytes BuildRos1Bag(const std::vector<TestTopic>& topics,
                          const std::vector<TestMessage>& messages, const std::string& compression,
                          bool indexed = true, bool misleading_index_length = false) {
  Bytes chunk;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    Ros1Connection(chunk, static_cast<int>(i), topics[i]);
  }
  for (const TestMessage& m : messages) {
    Bytes h;
    Ros1Field(h, "op", {0x02});
    Ros1Field(h, "conn", Le<std::uint32_t>(static_cast<std::uint32_t>(m.connection)));
    const std::uint64_t t = static_cast<std::uint64_t>(m.time_ns / 1000000000) |
                            (static_cast<std::uint64_t>(m.time_ns % 1000000000) << 32);
    Ros1Field(h, "time", Le<std::uint64_t>(t));
    Ros1Record(chunk, h, m.data);
  }
  const Bytes packed = Compress(chunk, compression);
  Bytes body;
  {
    Bytes h;
    Ros1Field(h, "op", {0x05});
    Ros1Field(h, "compression", Str(compression));
    Ros1Field(h, "size", Le<std::uint32_t>(static_cast<std::uint32_t>(chunk.size())));
    Ros1Record(body, h, packed);
  }
  if (misleading_index_length) {
    // An index-data record whose data length claims more than it holds (as in some old bags):
    // readers that walk record by record lose their way; the chunk-info index stays right.
    Bytes h;
    Ros1Field(h, "op", {0x04});
    Ros1Field(h, "ver", Le<std::uint32_t>(1));
    Ros1Field(h, "conn", Le<std::uint32_t>(0));
    Ros1Field(h, "count", Le<std::uint32_t>(0));
    PutRaw<std::uint32_t>(body, static_cast<std::uint32_t>(h.size()));
    body.insert(body.end(), h.begin(), h.end());
    PutRaw<std::uint32_t>(body, 1000000);
  }
  Bytes out = Str("#ROSBAG V2.0\n");
  Bytes bag_header_record;
  const std::size_t header_size = 4 + (4 + 3 + 1) + (4 + 10 + 8) + (4 + 11 + 4) + (4 + 12 + 4) + 4 +
                                  16;  // fields + data length + padding
  const std::uint64_t index_pos = out.size() + header_size + body.size();
  {
    Bytes h;
    Ros1Field(h, "op", {0x03});
    Ros1Field(h, "index_pos", Le<std::uint64_t>(indexed ? index_pos : 0));
    Ros1Field(h, "conn_count", Le<std::uint32_t>(static_cast<std::uint32_t>(topics.size())));
    Ros1Field(h, "chunk_count", Le<std::uint32_t>(1));
    Ros1Record(out, h, Bytes(16, ' '));
  }
  out.insert(out.end(), body.begin(), body.end());
  const std::uint64_t chunk_pos = out.size() - body.size();
  for (std::size_t i = 0; i < topics.size(); ++i) {
    Ros1Connection(out, static_cast<int>(i), topics[i]);
  }
  if (indexed) {
    Bytes h;
    Ros1Field(h, "op", {0x06});
    Ros1Field(h, "ver", Le<std::uint32_t>(1));
    Ros1Field(h, "chunk_pos", Le<std::uint64_t>(chunk_pos));
    Ros1Field(h, "start_time", Le<std::uint64_t>(0));
    Ros1Field(h, "end_time", Le<std::uint64_t>(0));
    Ros1Field(h, "count", Le<std::uint32_t>(0));
    Ros1Record(out, h, {});
  }
  return out;
}

// ---- MCAP ----
inline void McapString(Bytes& out, const std::string& s) {
  PutRaw<std::uint32_t>(out, static_cast<std::uint32_t>(s.size()));
  PutBytes(out, s);
}
inline void McapRecord(Bytes& out, std::uint8_t op, const Bytes& content) {
  out.push_back(op);
  PutRaw<std::uint64_t>(out, content.size());
  out.insert(out.end(), content.begin(), content.end());
}

/// compression: "", "zstd" or "lz4". Messages are CDR.
inline Bytes BuildMcap(const std::vector<TestTopic>& topics,
                       const std::vector<TestMessage>& messages, const std::string& compression) {
  Bytes out = Str("\x89MCAP0\r\n");
  {
    Bytes c;
    McapString(c, "ros2");
    McapString(c, "gridslam-test");
    McapRecord(out, 0x01, c);
  }
  Bytes records;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    Bytes s;
    PutRaw<std::uint16_t>(s, static_cast<std::uint16_t>(i + 1));
    McapString(s, topics[i].type);
    McapString(s, "ros2msg");
    McapString(s, "");
    McapRecord(records, 0x03, s);
    Bytes c;
    PutRaw<std::uint16_t>(c, static_cast<std::uint16_t>(i));
    PutRaw<std::uint16_t>(c, static_cast<std::uint16_t>(i + 1));
    McapString(c, topics[i].topic);
    McapString(c, "cdr");
    PutRaw<std::uint32_t>(c, 0);  // metadata map
    McapRecord(records, 0x04, c);
  }
  for (std::size_t k = 0; k < messages.size(); ++k) {
    const TestMessage& m = messages[k];
    Bytes c;
    PutRaw<std::uint16_t>(c, static_cast<std::uint16_t>(m.connection));
    PutRaw<std::uint32_t>(c, static_cast<std::uint32_t>(k));
    PutRaw<std::uint64_t>(c, static_cast<std::uint64_t>(m.time_ns));
    PutRaw<std::uint64_t>(c, static_cast<std::uint64_t>(m.time_ns));
    c.insert(c.end(), m.data.begin(), m.data.end());
    McapRecord(records, 0x05, c);
  }
  const Bytes packed = Compress(records, compression);
  {
    Bytes c;
    PutRaw<std::uint64_t>(c, 0);
    PutRaw<std::uint64_t>(c, 0);
    PutRaw<std::uint64_t>(c, records.size());
    PutRaw<std::uint32_t>(c, static_cast<std::uint32_t>(
                                 crc32(0L, records.data(), static_cast<uInt>(records.size()))));
    McapString(c, compression);
    PutRaw<std::uint64_t>(c, packed.size());
    c.insert(c.end(), packed.begin(), packed.end());
    McapRecord(out, 0x06, c);
  }
  McapRecord(out, 0x0F, Le<std::uint32_t>(0));
  {
    Bytes c;
    PutRaw<std::uint64_t>(c, 0);
    PutRaw<std::uint64_t>(c, 0);
    PutRaw<std::uint32_t>(c, 0);
    McapRecord(out, 0x02, c);
  }
  PutBytes(out, "\x89MCAP0\r\n");
  return out;
}

}  // namespace gridslam::recording::testing
