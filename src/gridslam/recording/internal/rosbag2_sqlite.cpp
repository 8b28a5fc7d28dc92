// rosbag2 sqlite3 storage: tables topics(id, name, type, serialization_format, ...) and
// messages(id, topic_id, timestamp, data), data being CDR with its encapsulation header.
#include <map>
#include <memory>

#include "gridslam/recording/internal/bag_container.hpp"

#include <sqlite3.h>

namespace gridslam::recording::internal {
namespace {

using Db = std::unique_ptr<sqlite3, decltype(&sqlite3_close)>;
using Stmt = std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)>;

Result<Stmt> Prepare(sqlite3* db, const char* sql, const std::string& file) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &raw, nullptr) != SQLITE_OK) {
    Stmt guard(raw, &sqlite3_finalize);
    return InvalidInput(std::string("not a rosbag2 database (") + sqlite3_errmsg(db) + ")", file);
  }
  return Stmt(raw, &sqlite3_finalize);
}

std::string Column(sqlite3_stmt* s, int i) {
  const unsigned char* text = sqlite3_column_text(s, i);
  return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

Status ReadOne(const std::string& file, std::vector<BagTopic>* topics, const MessageSink& sink) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  Db db(raw, &sqlite3_close);
  if (rc != SQLITE_OK) {
    return InvalidInput(std::string("cannot open the database: ") + sqlite3_errmsg(raw), file);
  }
  auto topic_rows =
      Prepare(db.get(), "SELECT id, name, type, serialization_format FROM topics", file);
  if (!topic_rows.ok()) {
    return topic_rows.error();
  }
  std::map<std::int64_t, std::size_t> ids;
  int step = 0;
  while ((step = sqlite3_step(topic_rows.value().get())) == SQLITE_ROW) {
    sqlite3_stmt* s = topic_rows.value().get();
    const std::string name = Column(s, 1);
    const std::string type = Column(s, 2);
    const std::string format = Column(s, 3);
    std::size_t index = topics->size();
    for (std::size_t i = 0; i < topics->size(); ++i) {
      if ((*topics)[i].topic == name && (*topics)[i].type == type) {
        index = i;
      }
    }
    if (index == topics->size()) {
      topics->push_back(
          {name, format == "cdr" ? type : "(" + format + ") " + type, MessageEncoding::kCdr, 0});
    }
    ids[sqlite3_column_int64(s, 0)] = index;
  }
  if (step != SQLITE_DONE) {
    return InvalidInput(std::string("corrupt rosbag2 database: ") + sqlite3_errmsg(db.get()), file);
  }
  auto rows = Prepare(
      db.get(), "SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id", file);
  if (!rows.ok()) {
    return rows.error();
  }
  while ((step = sqlite3_step(rows.value().get())) == SQLITE_ROW) {
    sqlite3_stmt* s = rows.value().get();
    auto it = ids.find(sqlite3_column_int64(s, 0));
    if (it == ids.end()) {
      return InvalidInput("a message refers to an unknown topic id", file);
    }
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(s, 2));
    const auto size = static_cast<std::size_t>(sqlite3_column_bytes(s, 2));
    ++(*topics)[it->second].count;
    GRIDSLAM_RETURN_IF_ERROR(
        sink(it->second, sqlite3_column_int64(s, 1), std::span<const std::uint8_t>(data, size)));
  }
  if (step != SQLITE_DONE) {
    return InvalidInput(std::string("corrupt rosbag2 database: ") + sqlite3_errmsg(db.get()), file);
  }
  return Status::Ok();
}

}  // namespace

Status ReadRosbag2Sqlite(const std::vector<std::string>& db3_files, std::vector<BagTopic>* topics,
                         const MessageSink& sink) {
  for (const std::string& file : db3_files) {
    GRIDSLAM_RETURN_IF_ERROR(ReadOne(file, topics, sink));
  }
  return Status::Ok();
}

}  // namespace gridslam::recording::internal
