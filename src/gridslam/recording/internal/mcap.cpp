// MCAP (https://mcap.dev/spec): 8-byte magic, then records <u8 opcode><u64 length><content>.
// Schema (3) and Channel (4) records build the topic table, Message (5) records carry data,
// Chunk (6) records hold further records compressed with "", "lz4" (LZ4 frame) or "zstd",
// checked against their CRC-32 when it is non-zero. Reading stops at DataEnd (15) or Footer (2).
#include <map>
#include <string_view>

#include <zlib.h>

#include "gridslam/recording/internal/bag_container.hpp"
#include "gridslam/recording/internal/byte_reader.hpp"
#include "gridslam/recording/internal/decompress.hpp"

namespace gridslam::recording::internal {
namespace {

constexpr std::uint8_t kOpFooter = 0x02;
constexpr std::uint8_t kOpSchema = 0x03;
constexpr std::uint8_t kOpChannel = 0x04;
constexpr std::uint8_t kOpMessage = 0x05;
constexpr std::uint8_t kOpChunk = 0x06;
constexpr std::uint8_t kOpDataEnd = 0x0F;

std::string McapString(ByteReader& r) {
  const std::uint32_t n = r.U32();
  if (n > r.remaining()) {
    r.Fail();
    return {};
  }
  return r.String(n);
}

class McapWalker {
 public:
  McapWalker(std::vector<BagTopic>* topics, const MessageSink& sink)
      : topics_(topics), sink_(sink) {}

  bool finished() const { return finished_; }

  Status Walk(std::span<const std::uint8_t> bytes, std::size_t base, bool in_chunk) {
    ByteReader r(bytes);
    while (!r.AtEnd() && !finished_) {
      const std::size_t at = base + r.position();
      const std::uint8_t op = r.U8();
      const std::uint64_t len = r.U64();
      if (!r.ok() || len > r.remaining()) {
        return InvalidInput(std::string("MCAP record at byte ") + std::to_string(at) +
                            " runs past the end of the " +
                            (in_chunk ? "chunk (corrupt chunk)" : "file (truncated file)"));
      }
      ByteReader content(r.Bytes(static_cast<std::size_t>(len)));
      Status s = Status::Ok();
      switch (op) {
        case kOpSchema:
          s = Schema(content, at);
          break;
        case kOpChannel:
          s = Channel(content, at);
          break;
        case kOpMessage:
          s = Message(content, at);
          break;
        case kOpChunk:
          if (in_chunk) {
            return InvalidInput("MCAP chunk nested in a chunk at byte " + std::to_string(at));
          }
          s = Chunk(content, at);
          break;
        case kOpDataEnd:
        case kOpFooter:
          finished_ = !in_chunk;
          break;
        default:
          break;
      }
      GRIDSLAM_RETURN_IF_ERROR(s);
    }
    return Status::Ok();
  }

 private:
  Status Schema(ByteReader& r, std::size_t at) {
    const std::uint16_t id = r.U16();
    std::string name = McapString(r);
    McapString(r);  // encoding
    if (!r.ok()) {
      return InvalidInput("malformed MCAP schema record at byte " + std::to_string(at));
    }
    schemas_[id] = std::move(name);
    return Status::Ok();
  }

  Status Channel(ByteReader& r, std::size_t at) {
    const std::uint16_t id = r.U16();
    const std::uint16_t schema = r.U16();
    std::string topic = McapString(r);
    const std::string encoding = McapString(r);
    if (!r.ok()) {
      return InvalidInput("malformed MCAP channel record at byte " + std::to_string(at));
    }
    if (channels_.contains(id)) {
      return Status::Ok();
    }
    auto it = schemas_.find(schema);
    std::string type = it != schemas_.end() ? it->second : std::string();
    const MessageEncoding e = encoding == "ros1" ? MessageEncoding::kRos1 : MessageEncoding::kCdr;
    if (encoding != "ros1" && encoding != "cdr") {
      type = "(" + encoding + ") " + type;  // not decodable: listed, never read
    }
    channels_[id] = topics_->size();
    topics_->push_back({std::move(topic), std::move(type), e, 0});
    return Status::Ok();
  }

  Status Message(ByteReader& r, std::size_t at) {
    const std::uint16_t channel = r.U16();
    r.U32();  // sequence
    const std::uint64_t log_time = r.U64();
    r.U64();  // publish time
    auto data = r.Rest();
    if (!r.ok()) {
      return InvalidInput("malformed MCAP message record at byte " + std::to_string(at));
    }
    auto it = channels_.find(channel);
    if (it == channels_.end()) {
      return InvalidInput("MCAP message at byte " + std::to_string(at) +
                          " refers to unknown channel " + std::to_string(channel));
    }
    ++(*topics_)[it->second].count;
    return sink_(it->second, static_cast<std::int64_t>(log_time), data);
  }

  Status Chunk(ByteReader& r, std::size_t at) {
    r.U64();  // message start time
    r.U64();  // message end time
    const std::uint64_t size = r.U64();
    const std::uint32_t crc = r.U32();
    const std::string compression = McapString(r);
    const std::uint64_t records_len = r.U64();
    if (!r.ok() || records_len > r.remaining()) {
      return InvalidInput("malformed MCAP chunk header at byte " + std::to_string(at));
    }
    auto records = r.Bytes(static_cast<std::size_t>(records_len));
    Compression c = Compression::kNone;
    if (compression == "zstd") {
      c = Compression::kZstd;
    } else if (compression == "lz4") {
      c = Compression::kLz4Frame;
    } else if (!compression.empty()) {
      return InvalidInput("MCAP chunk at byte " + std::to_string(at) +
                          " has unknown compression '" + compression + "'");
    }
    auto content = Decompress(records, c, static_cast<std::size_t>(size));
    if (!content.ok()) {
      return InvalidInput("MCAP chunk at byte " + std::to_string(at) + ": " +
                          content.error().message);
    }
    if (crc != 0) {
      const auto actual = static_cast<std::uint32_t>(
          crc32(0L, content.value().data(), static_cast<uInt>(content.value().size())));
      if (actual != crc) {
        return InvalidInput("MCAP chunk at byte " + std::to_string(at) +
                            " fails its CRC check (corrupt chunk)");
      }
    }
    return Walk(content.value(), 0, true);
  }

  std::vector<BagTopic>* topics_;
  const MessageSink& sink_;
  std::map<std::uint16_t, std::string> schemas_;
  std::map<std::uint16_t, std::size_t> channels_;
  bool finished_ = false;
};

}  // namespace

Status ReadMcap(std::span<const std::uint8_t> file, std::vector<BagTopic>* topics,
                const MessageSink& sink) {
  if (file.size() < kMcapMagic.size() ||
      std::string_view(reinterpret_cast<const char*>(file.data()), kMcapMagic.size()) !=
          kMcapMagic) {
    return InvalidInput("not an MCAP file (wrong magic)");
  }
  McapWalker walker(topics, sink);
  GRIDSLAM_RETURN_IF_ERROR(walker.Walk(file.subspan(kMcapMagic.size()), kMcapMagic.size(), false));
  if (!walker.finished()) {
    return InvalidInput("truncated MCAP file: it ends before its DataEnd/Footer record");
  }
  return Status::Ok();
}

}  // namespace gridslam::recording::internal
