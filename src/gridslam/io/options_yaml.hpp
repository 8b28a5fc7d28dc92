// Generic YAML reader and writer for options structs that follow the Visit() convention of
// common/options.hpp. Unknown keys are errors naming the file and key; missing keys keep their
// defaults. The writer prints every key with its documentation as a comment, which is what
// `gridslam --print-config` shows and what every run saves beside its results.
#pragma once

#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "gridslam/common/result.hpp"

namespace gridslam::io {

namespace internal {

/// Reads fields from one YAML mapping; records the first error and the keys it knows.
class YamlReadVisitor {
 public:
  YamlReadVisitor(const YAML::Node& node, std::string path, std::string file,
                  std::map<std::string, long>* lines)
      : node_(node), path_(std::move(path)), file_(std::move(file)), lines_(lines) {}

  template <typename T>
  void operator()(const char* key, T& field, const char* /*doc*/) {
    known_.insert(key);
    if (!status_.ok() || !node_ || !node_[key]) {
      return;
    }
    lines_->emplace(Qualified(key), node_[key].Mark().line + 1);
    try {
      if constexpr (std::is_same_v<T, std::vector<double>>) {
        field = node_[key].template as<std::vector<double>>();
      } else {
        field = node_[key].template as<T>();
      }
    } catch (const YAML::Exception& e) {
      status_ = InvalidInput("option '" + Qualified(key) +
                                 "': cannot read a value of the right "
                                 "type (" +
                                 e.msg + ")",
                             file_, node_[key].Mark().line + 1);
    }
  }

  template <typename Sub>
  void Section(const char* key, Sub& sub, const char* /*doc*/) {
    known_.insert(key);
    if (!status_.ok() || !node_ || !node_[key]) {
      return;
    }
    if (!node_[key].IsMap()) {
      status_ = InvalidInput("section '" + Qualified(key) + "' must be a mapping", file_,
                             node_[key].Mark().line + 1);
      return;
    }
    YamlReadVisitor child(node_[key], Qualified(key), file_, lines_);
    sub.Visit(child);
    status_ = child.Finish();
  }

  /// Checks for unknown, duplicate and non-scalar keys; returns the first error.
  Status Finish() {
    if (!status_.ok() || !node_ || !node_.IsMap()) {
      return status_;
    }
    std::set<std::string> seen;
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) {
        return InvalidInput("a key in '" + (path_.empty() ? std::string("the top level") : path_) +
                                "' is not a plain name",
                            file_, kv.first.Mark().line + 1);
      }
      const auto key = kv.first.as<std::string>();
      if (!seen.insert(key).second) {
        return InvalidInput("option '" + Qualified(key) + "' given twice", file_,
                            kv.first.Mark().line + 1);
      }
      if (known_.count(key) == 0) {
        return InvalidInput("unknown option '" + Qualified(key) + "'", file_,
                            kv.first.Mark().line + 1);
      }
    }
    return status_;
  }

  /// The line of every option the file sets, by qualified name ("fusion.resolution").
  using LineMap = std::map<std::string, long>;

 private:
  std::string Qualified(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  YAML::Node node_;
  std::string path_;
  std::string file_;
  std::set<std::string> known_;
  std::map<std::string, long>* lines_;
  Status status_;
};

/// Names the file, and the line of the option a validation error is about (the longest option
/// name set in the file that the message mentions), in a Validate() error.
inline Status LocateValidationError(Status status, const std::string& file,
                                    const std::map<std::string, long>& lines) {
  if (status.ok()) {
    return status;
  }
  Error error = status.error();
  if (error.file.empty()) {
    error.file = file;
    std::size_t best = 0;
    for (const auto& [key, line] : lines) {
      const std::size_t at = error.message.find(key);
      if (at == std::string::npos || key.size() <= best) {
        continue;
      }
      const std::size_t after = at + key.size();
      const bool whole = after >= error.message.size() ||
                         (std::isalnum(static_cast<unsigned char>(error.message[after])) == 0 &&
                          error.message[after] != '_');
      if (whole) {
        best = key.size();
        error.line = line;
      }
    }
  }
  return error;
}

/// Writes fields as commented YAML.
class YamlWriteVisitor {
 public:
  explicit YamlWriteVisitor(std::ostringstream& out, int indent = 0) : out_(out), indent_(indent) {}

  template <typename T>
  void operator()(const char* key, T& field, const char* doc) {
    out_ << Pad() << "# " << doc << "\n" << Pad() << key << ": ";
    if constexpr (std::is_same_v<T, bool>) {
      out_ << (field ? "true" : "false");
    } else if constexpr (std::is_same_v<T, std::string>) {
      out_ << '"' << field << '"';
    } else if constexpr (std::is_same_v<T, std::vector<double>>) {
      out_ << "[";
      for (std::size_t i = 0; i < field.size(); ++i) {
        out_ << (i > 0 ? ", " : "") << Number(field[i]);
      }
      out_ << "]";
    } else if constexpr (std::is_floating_point_v<T>) {
      out_ << Number(static_cast<double>(field));
    } else {
      out_ << field;
    }
    out_ << "\n";
  }

  template <typename Sub>
  void Section(const char* key, Sub& sub, const char* doc) {
    out_ << Pad() << "# " << doc << "\n" << Pad() << key << ":\n";
    YamlWriteVisitor child(out_, indent_ + 2);
    sub.Visit(child);
  }

 private:
  static std::string Number(double v) {
    // YAML 1.2 spells the special values .inf, -.inf and .nan ("inf" would read as a string).
    if (std::isnan(v)) {
      return ".nan";
    }
    if (std::isinf(v)) {
      return v > 0 ? ".inf" : "-.inf";
    }
    std::ostringstream s;
    s.precision(12);
    s << v;
    std::string text = s.str();
    if (text.find_first_of(".eEn") == std::string::npos) {
      text += ".0";
    }
    return text;
  }
  std::string Pad() const { return std::string(static_cast<std::size_t>(indent_), ' '); }
  std::ostringstream& out_;
  int indent_;
};

/// 1-based line of the first key of `root` whose dotted path ends in `dotted` (e.g.
/// "refinement.max_points" matches loop_closure.refinement.max_points); 0 if none.
long FindOptionLine(const YAML::Node& root, const std::string& dotted,
                    const std::string& prefix = "");

/// The line in `root` of the first option named in a validation message ("invalid option:
/// fusion.resolution > 0"); 0 if the message names none that `root` sets.
long FindValidationLine(const YAML::Node& root, const std::string& message);

}  // namespace internal

/// Overrides `options` from the YAML text `yaml` (`file` names it in errors), without validating.
template <typename Options>
Status ApplyOptionsFromString(const std::string& yaml, const std::string& file, Options& options,
                              YAML::Node* parsed = nullptr,
                              std::map<std::string, long>* lines = nullptr) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    return InvalidInput("YAML syntax error: " + e.msg, file, e.mark.line + 1);
  }
  if (parsed != nullptr) {
    *parsed = root;
  }
  if (root.IsNull()) {
    return Status::Ok();
  }
  if (!root.IsMap()) {
    return InvalidInput("configuration must be a YAML mapping", file, 1);
  }
  std::map<std::string, long> local;
  try {
    internal::YamlReadVisitor visitor(root, "", file, lines != nullptr ? lines : &local);
    options.Visit(visitor);
    return visitor.Finish();
  } catch (const YAML::Exception& e) {
    return InvalidInput("cannot read the configuration: " + e.msg, file, e.mark.line + 1);
  }
}

/// Overrides `options` from the YAML text `yaml` (`file` names it in errors), then validates. A
/// validation error names `file` and the line of the offending key when the text sets it.
template <typename Options>
Status LoadOptionsFromString(const std::string& yaml, const std::string& file, Options& options) {
  YAML::Node root;
  std::map<std::string, long> lines;
  GRIDSLAM_RETURN_IF_ERROR(ApplyOptionsFromString(yaml, file, options, &root, &lines));
  Status status = internal::LocateValidationError(options.Validate(), file, lines);
  if (!status.ok() && status.error().line == 0 && status.error().file == file && root.IsMap()) {
    Error error = status.error();
    error.line = internal::FindValidationLine(root, error.message);
    return error;
  }
  return status;
}

/// Applies one `section.key=value` override (the value is read as YAML: a scalar or a flow
/// sequence such as [0.2, 0, 0]), without validating. Errors name the assignment.
template <typename Options>
Status ApplyOptionOverride(const std::string& assignment, Options& options) {
  const std::string where = "--set " + assignment;
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    return InvalidInput("expected KEY=VALUE, e.g. fusion.resolution=0.1", where);
  }
  const std::string key = assignment.substr(0, eq);
  // Dot-separated parts of [A-Za-z0-9_]+ (no std::regex: it trips gcc 12's
  // -Wmaybe-uninitialized under the sanitizers).
  bool well_formed = key.front() != '.' && key.back() != '.' && key.find("..") == std::string::npos;
  for (const char c : key) {
    well_formed =
        well_formed && (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.');
  }
  if (!well_formed) {
    return InvalidInput("'" + key + "' is not an option name (section.key)", where);
  }
  // section.sub.key=value as the YAML mapping {section: {sub: {key: value}}}.
  std::string yaml = "{";
  std::string closing = "}";
  std::size_t start = 0;
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
    yaml += key.substr(start, dot - start) + ": {";
    closing += "}";
    start = dot + 1;
  }
  yaml += key.substr(start) + ": " + assignment.substr(eq + 1) + closing;
  Status status = ApplyOptionsFromString(yaml, where, options);
  if (!status.ok()) {
    Error error = status.error();
    error.file = where;
    error.line = 0;
    return error;
  }
  return status;
}

/// Reads a YAML file into `options` (keys absent from the file keep their values).
template <typename Options>
Status LoadOptionsFromFile(const std::string& path, Options& options);

/// The options as commented YAML.
template <typename Options>
std::string OptionsToYaml(Options options) {
  std::ostringstream out;
  internal::YamlWriteVisitor visitor(out);
  options.Visit(visitor);
  return out.str();
}

/// Reads a whole text file; NotFound if it cannot be opened.
Result<std::string> ReadTextFile(const std::string& path);

template <typename Options>
Status LoadOptionsFromFile(const std::string& path, Options& options) {
  auto text = ReadTextFile(path);
  if (!text.ok()) {
    return text.error();
  }
  return LoadOptionsFromString(text.value(), path, options);
}

}  // namespace gridslam::io
