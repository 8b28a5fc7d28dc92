#include "gridslam/io/options_yaml.hpp"

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
  // Every dotted option name in the message ("fusion.resolution"): runs of [a-z0-9_.] whose
  // dot-separated parts start with a letter or '_', with at least one dot. (Scanned by hand:
  // std::regex trips gcc 12's -Wmaybe-uninitialized under the sanitizers.)
  const auto name_char = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
  };
  std::size_t i = 0;
  while (i < message.size()) {
    if (!name_char(message[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < message.size() && name_char(message[end])) {
      ++end;
    }
    std::string token = message.substr(i, end - i);
    while (!token.empty() && token.back() == '.') {
      token.pop_back();  // a sentence's full stop
    }
    bool valid = token.find('.') != std::string::npos;
    for (std::size_t k = 0; valid && k < token.size(); ++k) {
      const bool starts_part = k == 0 || token[k - 1] == '.';
      if (starts_part && !((token[k] >= 'a' && token[k] <= 'z') || token[k] == '_')) {
        valid = false;
      }
    }
    if (valid) {
      if (const long line = FindOptionLine(root, token); line > 0) {
        return line;
      }
    }
    i = end;
  }
  return 0;
}

}  // namespace gridslam::io::internal
