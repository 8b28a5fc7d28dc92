#include "gridslam/io/options_yaml.hpp"

#include <regex>

namespace gridslam::io::internal {

long FindOptionLine(const YAML::Node& root, const std::string& dotted, const std::string& prefix) {
  if (!root.IsMap()) {
    return 0;
  }
  for (const auto& kv : root) {
    const std::string path =
        prefix.empty() ? kv.first.as<std::string>() : prefix + "." + kv.first.as<std::string>();
    const bool ends_with =
        path.size() >= dotted.size() &&
        path.compare(path.size() - dotted.size(), dotted.size(), dotted) == 0 &&
        (path.size() == dotted.size() || path[path.size() - dotted.size() - 1] == '.');
    if (ends_with) {
      return kv.first.Mark().line + 1;
    }
    if (const long line = FindOptionLine(kv.second, dotted, path); line > 0) {
      return line;
    }
  }
  return 0;
}

long FindValidationLine(const YAML::Node& root, const std::string& message) {
  static const std::regex kName("[a-z_][a-z0-9_]*(\\.[a-z_][a-z0-9_]*)+");
  for (auto it = std::sregex_iterator(message.begin(), message.end(), kName);
       it != std::sregex_iterator(); ++it) {
    if (const long line = FindOptionLine(root, it->str()); line > 0) {
      return line;
    }
  }
  return 0;
}

}  // namespace gridslam::io::internal
