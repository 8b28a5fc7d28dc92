#include "gridslam/io/relations_io.hpp"

#include <cmath>
#include <cstdio>

#include "gridslam/io/atomic_file.hpp"
#include "gridslam/io/internal/carmen_line.hpp"
#include "gridslam/io/internal/gz_line_reader.hpp"
#include "gridslam/io/internal/number_parse.hpp"

namespace gridslam::io {

Result<std::vector<eval::Relation>> ReadRelations(const std::string& path) {
  static constexpr const char* kFields[8] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};
  internal::GzLineReader reader;
  GRIDSLAM_RETURN_IF_ERROR(reader.Open(path));
  std::vector<eval::Relation> relations;
  std::string line;
  std::vector<std::string_view> tokens;
  Status status;
  long line_number = 0;
  while (reader.ReadLine(line, status)) {
    ++line_number;
    internal::SplitFields(line, tokens);
    if (tokens.empty() || tokens[0].front() == '#') {
      continue;
    }
    if (tokens.size() < 8) {
      return InvalidInput("relation has " + std::to_string(tokens.size()) + " fields; field '" +
                              kFields[tokens.size()] + "' missing (t1 t2 x y z roll pitch yaw)",
                          path, line_number);
    }
    eval::Relation r;
    for (int k = 0; k < 2; ++k) {
      const auto t = ParseSeconds(tokens[static_cast<std::size_t>(k)]);
      if (!t) {
        return InvalidInput(std::string("field '") + kFields[k] + "': cannot read '" +
                                std::string(tokens[static_cast<std::size_t>(k)]) + "' as seconds",
                            path, line_number);
      }
      (k == 0 ? r.t1 : r.t2) = *t;
    }
    double v[6];
    for (std::size_t k = 2; k < 8; ++k) {
      if (!internal::ParseDouble(tokens[k], v[k - 2]) || !std::isfinite(v[k - 2])) {
        return InvalidInput(std::string("field '") + kFields[k] + "': cannot read '" +
                                std::string(tokens[k]) + "' as a number",
                            path, line_number);
      }
    }
    r.T_1_2 = Pose2(v[0], v[1], v[5]);
    relations.push_back(r);
  }
  if (!status.ok()) {
    return status.error();
  }
  return relations;
}

Status WriteRelations(const std::string& path, const std::vector<eval::Relation>& relations) {
  std::string out;
  out.reserve(relations.size() * 120);
  char buffer[192];
  for (const auto& r : relations) {
    out += FormatSeconds(r.t1, 6);
    out += ' ';
    out += FormatSeconds(r.t2, 6);
    const int n = std::snprintf(buffer, sizeof(buffer), " %.17g %.17g 0 0 0 %.17g\n", r.T_1_2.x(),
                                r.T_1_2.y(), r.T_1_2.theta());
    out.append(buffer, static_cast<std::size_t>(n));
  }
  return WriteFileAtomically(path, out);
}

}  // namespace gridslam::io
