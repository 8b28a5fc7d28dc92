// ROS 1 bag v2.0 (http://wiki.ros.org/Bags/Format/2.0): after the 13-byte magic, records of
// <u32 header_len><header: fields u32 len + "name=value"><u32 data_len><data>. Chunks (op 5)
// hold connection (op 7) and message (op 2) records, compressed with "none", "bz2" or "lz4"
// (LZ4 frame format). Index (op 4) and chunk-info (op 6) records are skipped.
#include <map>
#include <optional>
#include <string_view>

#include "gridslam/recording/internal/bag_container.hpp"
#include "gridslam/recording/internal/byte_reader.hpp"
#include "gridslam/recording/internal/decompress.hpp"

namespace gridslam::recording::internal {
namespace {

constexpr std::uint8_t kOpMessage = 0x02;
constexpr std::uint8_t kOpBagHeader = 0x03;
constexpr std::uint8_t kOpChunk = 0x05;
constexpr std::uint8_t kOpChunkInfo = 0x06;
constexpr std::uint8_t kOpConnection = 0x07;

using Fields = std::map<std::string, std::span<const std::uint8_t>, std::less<>>;

std::optional<Fields> ParseFields(std::span<const std::uint8_t> header) {
  Fields fields;
  ByteReader r(header);
  while (!r.AtEnd()) {
    const std::uint32_t len = r.U32();
    auto field = r.Bytes(len);
    if (!r.ok()) {
      return std::nullopt;
    }
    const auto* begin = reinterpret_cast<const char*>(field.data());
    const std::string_view text(begin, field.size());
    const std::size_t eq = text.find('=');
    if (eq == std::string_view::npos) {
      return std::nullopt;
    }
    fields[std::string(text.substr(0, eq))] = field.subspan(eq + 1);
  }
  return fields;
}

std::string FieldString(const Fields& f, std::string_view name) {
  auto it = f.find(name);
  if (it == f.end()) {
    return {};
  }
  return {reinterpret_cast<const char*>(it->second.data()), it->second.size()};
}

template <class T>
std::optional<T> FieldValue(const Fields& f, std::string_view name) {
  auto it = f.find(name);
  if (it == f.end() || it->second.size() != sizeof(T)) {
    return std::nullopt;
  }
  ByteReader r(it->second);
  return r.Read<T>();
}

class Ros1Walker {
 public:
  Ros1Walker(std::vector<BagTopic>* topics, const MessageSink& sink)
      : topics_(topics), sink_(sink) {}

  // Walks the records of `bytes` (the file after the magic, or one chunk's content).
  Status Walk(std::span<const std::uint8_t> bytes, std::size_t base, bool in_chunk) {
    ByteReader r(bytes);
    while (!r.AtEnd()) {
      const std::size_t at = base + r.position();
      const std::uint32_t header_len = r.U32();
      auto header = r.Bytes(header_len);
      const std::uint32_t data_len = r.U32();
      auto data = r.Bytes(data_len);
      if (!r.ok()) {
        return InvalidInput(std::string(in_chunk ? "chunk record" : "record") + " at byte " +
                            std::to_string(at) + " runs past the end of the " +
                            (in_chunk ? "chunk (corrupt chunk)" : "file (truncated bag)"));
      }
      const auto fields = ParseFields(header);
      const auto op = fields ? FieldValue<std::uint8_t>(*fields, "op") : std::nullopt;
      if (!op) {
        return InvalidInput("record at byte " + std::to_string(at) +
                            " has a malformed header (corrupt bag)");
      }
      Status s = Status::Ok();
      if (*op == kOpBagHeader && !in_chunk) {
        const auto index_pos = FieldValue<std::uint64_t>(*fields, "index_pos");
        if (index_pos && *index_pos > base + bytes.size()) {
          return InvalidInput("truncated bag: its index starts at byte " +
                              std::to_string(*index_pos) + " but the file has " +
                              std::to_string(base + bytes.size()) + " bytes");
        }
      } else if (*op == kOpChunk) {
        s = Chunk(*fields, data, at);
      } else if (*op == kOpConnection) {
        s = Connection(*fields, data, at);
      } else if (*op == kOpMessage) {
        s = Message(*fields, data, at);
      }
      GRIDSLAM_RETURN_IF_ERROR(s);
    }
    return Status::Ok();
  }

  // The index section: connection records (registered) and chunk-info records (positions).
  Status WalkIndex(std::span<const std::uint8_t> bytes, std::size_t base,
                   std::vector<std::uint64_t>* chunk_positions) {
    ByteReader r(bytes);
    while (!r.AtEnd()) {
      const std::size_t at = base + r.position();
      const std::uint32_t header_len = r.U32();
      auto header = r.Bytes(header_len);
      const std::uint32_t data_len = r.U32();
      auto data = r.Bytes(data_len);
      const auto fields = r.ok() ? ParseFields(header) : std::nullopt;
      const auto op = fields ? FieldValue<std::uint8_t>(*fields, "op") : std::nullopt;
      if (!op) {
        return InvalidInput("index record at byte " + std::to_string(at) +
                            " is truncated or malformed (truncated or corrupt bag)");
      }
      if (*op == kOpConnection) {
        GRIDSLAM_RETURN_IF_ERROR(Connection(*fields, data, at));
      } else if (*op == kOpChunkInfo) {
        const auto pos = FieldValue<std::uint64_t>(*fields, "chunk_pos");
        if (!pos) {
          return InvalidInput("chunk-info record at byte " + std::to_string(at) +
                              " has no chunk_pos");
        }
        chunk_positions->push_back(*pos);
      }
    }
    return Status::Ok();
  }

  // One chunk record at the start of `bytes`.
  Status WalkOne(std::span<const std::uint8_t> bytes, std::size_t at) {
    ByteReader r(bytes);
    const std::uint32_t header_len = r.U32();
    auto header = r.Bytes(header_len);
    const std::uint32_t data_len = r.U32();
    auto data = r.Bytes(data_len);
    if (!r.ok()) {
      return InvalidInput("chunk at byte " + std::to_string(at) +
                          " runs past the end of the file (truncated bag)");
    }
    const auto fields = ParseFields(header);
    const auto op = fields ? FieldValue<std::uint8_t>(*fields, "op") : std::nullopt;
    if (!op || *op != kOpChunk) {
      return InvalidInput("no chunk record at byte " + std::to_string(at) +
                          ", where the index points (corrupt bag)");
    }
    return Chunk(*fields, data, at);
  }

 private:
  Status Chunk(const Fields& f, std::span<const std::uint8_t> data, std::size_t at) {
    const std::string compression = FieldString(f, "compression");
    const auto size = FieldValue<std::uint32_t>(f, "size");
    Compression c = Compression::kNone;
    if (compression == "bz2") {
      c = Compression::kBz2;
    } else if (compression == "lz4") {
      c = Compression::kLz4Frame;
    } else if (compression != "none") {
      return InvalidInput("chunk at byte " + std::to_string(at) + " has unknown compression '" +
                          compression + "'");
    }
    if (!size) {
      return InvalidInput("chunk at byte " + std::to_string(at) + " has no size field");
    }
    auto content = Decompress(data, c, *size);
    if (!content.ok()) {
      return InvalidInput("chunk at byte " + std::to_string(at) + ": " + content.error().message);
    }
    return Walk(content.value(), 0, true);
  }

  Status Connection(const Fields& f, std::span<const std::uint8_t> data, std::size_t at) {
    const auto conn = FieldValue<std::uint32_t>(f, "conn");
    const auto info = ParseFields(data);
    if (!conn || !info) {
      return InvalidInput("connection record at byte " + std::to_string(at) + " is malformed");
    }
    if (connections_.contains(*conn)) {
      return Status::Ok();
    }
    std::string topic = FieldString(f, "topic");
    std::string type = FieldString(*info, "type");
    for (std::size_t i = 0; i < topics_->size(); ++i) {
      if ((*topics_)[i].topic == topic && (*topics_)[i].type == type) {
        connections_[*conn] = i;
        return Status::Ok();
      }
    }
    connections_[*conn] = topics_->size();
    topics_->push_back({std::move(topic), std::move(type), MessageEncoding::kRos1, 0});
    return Status::Ok();
  }

  Status Message(const Fields& f, std::span<const std::uint8_t> data, std::size_t at) {
    const auto conn = FieldValue<std::uint32_t>(f, "conn");
    const auto time = FieldValue<std::uint64_t>(f, "time");
    if (!conn || !time) {
      return InvalidInput("message record at byte " + std::to_string(at) + " is malformed");
    }
    auto it = connections_.find(*conn);
    if (it == connections_.end()) {
      return InvalidInput("message record at byte " + std::to_string(at) +
                          " refers to unknown connection " + std::to_string(*conn));
    }
    const auto sec = static_cast<std::int64_t>(*time & 0xffffffffULL);
    const auto nsec = static_cast<std::int64_t>(*time >> 32);
    ++(*topics_)[it->second].count;
    return sink_(it->second, sec * 1000000000LL + nsec, data);
  }

  std::vector<BagTopic>* topics_;
  const MessageSink& sink_;
  std::map<std::uint32_t, std::size_t> connections_;
};

}  // namespace

Status ReadRos1Bag(std::span<const std::uint8_t> file, std::vector<BagTopic>* topics,
                   const MessageSink& sink) {
  if (file.size() < kRos1Magic.size() ||
      std::string_view(reinterpret_cast<const char*>(file.data()), kRos1Magic.size()) !=
          kRos1Magic) {
    return InvalidInput("not a ROS 1 bag v2.0 (wrong magic)");
  }
  Ros1Walker walker(topics, sink);
  // Indexed bag: the bag header's index_pos leads to the connection and chunk-info records,
  // which give each chunk's position (as rosbag reads it; some writers put wrong lengths on
  // the index records between chunks, so the chunks are not walked back to back). An
  // unindexed bag (index_pos 0, e.g. a recording that was not closed) is walked sequentially.
  ByteReader r(file.subspan(kRos1Magic.size()));
  const std::uint32_t header_len = r.U32();
  const auto header = r.Bytes(header_len);
  const auto fields = r.ok() ? ParseFields(header) : std::nullopt;
  const auto op = fields ? FieldValue<std::uint8_t>(*fields, "op") : std::nullopt;
  if (!op || *op != kOpBagHeader) {
    return InvalidInput("the bag does not start with a bag header record (corrupt bag)");
  }
  const auto index_pos = FieldValue<std::uint64_t>(*fields, "index_pos");
  if (!index_pos || *index_pos == 0) {
    return walker.Walk(file.subspan(kRos1Magic.size()), kRos1Magic.size(), false);
  }
  if (*index_pos >= file.size()) {
    return InvalidInput("truncated bag: its index starts at byte " + std::to_string(*index_pos) +
                        " but the file has " + std::to_string(file.size()) + " bytes");
  }
  std::vector<std::uint64_t> chunk_positions;
  GRIDSLAM_RETURN_IF_ERROR(
      walker.WalkIndex(file.subspan(*index_pos), *index_pos, &chunk_positions));
  for (const std::uint64_t pos : chunk_positions) {
    if (pos >= file.size()) {
      return InvalidInput("truncated bag: chunk at byte " + std::to_string(pos) +
                          " is past the end of the file (" + std::to_string(file.size()) +
                          " bytes)");
    }
    GRIDSLAM_RETURN_IF_ERROR(walker.WalkOne(file.subspan(pos), pos));
  }
  return Status::Ok();
}

}  // namespace gridslam::recording::internal
