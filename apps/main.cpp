// gridslam: 2D laser graph-SLAM from the command line (docs/design.md §2).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <regex>
#include <string_view>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "gridslam/io/options_yaml.hpp"

#include "app_huge_pages.hpp"
#include "command.hpp"

namespace gridslam::app {

std::vector<CommandSpec>& Commands() {
  static std::vector<CommandSpec> commands;
  return commands;
}

int RegisterCommand(CommandSpec spec) {
  Commands().push_back(std::move(spec));
  return 0;
}

int ReportError(const Error& error) {
  std::fprintf(stderr, "gridslam: error: %s\n", error.ToString().c_str());
  return error.code == ErrorCode::kRuntime ? kExitRuntimeError : kExitBadInput;
}

namespace {

#ifndef GRIDSLAM_VERSION
#define GRIDSLAM_VERSION "unknown"
#endif

/// Options every command accepts, before or after its name (so each command's --help shows them).
struct CommonOptions {
  std::vector<std::string> set;  ///< --set KEY=VALUE, in order.
  std::optional<double> rate;    ///< --rate HZ (log.timestamp_rate), after --config.
};

void AddCommonOptions(CLI::App& app, AppContext& context, std::string& log_level,
                      CommonOptions& common) {
  app.add_option("--config", context.config_path,
                 "YAML configuration overriding the defaults (only the options it changes)")
      ->check(CLI::ExistingFile);
  app.add_option("--set", common.set,
                 "Override one option, KEY=VALUE with the value in YAML, e.g. "
                 "fusion.resolution=0.1 (repeatable; after --config)")
      ->type_name("KEY=VALUE");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.add_flag("--lenient", context.options.log.lenient,
               "Skip and count malformed log lines instead of failing");
  app.add_option("--rate", common.rate,
                 "Scan rate [Hz] for logs without timestamps (times are synthesized from message "
                 "order; log.timestamp_rate)");
  app.add_option("--scan-topic", context.bag.scan_topic,
                 "Bags: sensor_msgs/LaserScan topic (default: the only one)");
  app.add_option("--odom-topic", context.bag.odom_topic,
                 "Bags: nav_msgs/Odometry topic (default: the only one, else TF odom->base_link)");
  app.add_option("--odom-frame", context.bag.odom_frame,
                 "Bags: odometry from TF with this odometry frame (default odom)");
  app.add_option("--base-frame", context.bag.base_frame,
                 "Bags: robot frame (default: the odometry's child frame, else base_link)");
}

/// Levenshtein distance, for suggesting the command a typo meant.
std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The first word of argv that is neither an option nor an option's value: the command name.
std::string FirstWord(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg == "--config" || arg == "--set" || arg == "--log-level" || arg == "--rate" ||
        arg == "--scan-topic" || arg == "--odom-topic" || arg == "--odom-frame" ||
        arg == "--base-frame") {
      ++i;  // its value
    } else if (arg.empty() || arg[0] != '-') {
      return std::string(arg);
    }
  }
  return {};
}

/// An unknown command: the nearest one and the list, exit 2 (CLI11 would only say "The following
/// arguments were not expected").
std::optional<int> CheckCommandName(int argc, char** argv) {
  const std::string word = FirstWord(argc, argv);
  if (word.empty()) {
    return std::nullopt;
  }
  std::string names;
  const CommandSpec* nearest = nullptr;
  std::size_t best = 0;
  for (const CommandSpec& spec : Commands()) {
    if (spec.name == word) {
      return std::nullopt;
    }
    const std::size_t d = EditDistance(word, spec.name);
    if (nearest == nullptr || d < best) {
      nearest = &spec;
      best = d;
    }
  }
  for (const CommandSpec& spec : Commands()) {
    names += "\n  " + spec.name +
             std::string(12 - std::min<std::size_t>(spec.name.size(), 11), ' ') + spec.description;
  }
  std::fprintf(stderr, "gridslam: error: unknown command '%s'", word.c_str());
  if (nearest != nullptr && best <= std::max<std::size_t>(2, nearest->name.size() / 3)) {
    std::fprintf(stderr, "; did you mean '%s'?", nearest->name.c_str());
  }
  std::fprintf(stderr, "\ncommands:%s\nRun 'gridslam --help' for the options.\n", names.c_str());
  return kExitBadInput;
}

/// A validation error raised after --set overrides: names the --set that set the offending key.
Error AttributeToOverride(Error error, const std::vector<std::string>& sets) {
  static const std::regex kName("[a-z_][a-z0-9_]*(\\.[a-z_][a-z0-9_]*)+");
  for (auto it = std::sregex_iterator(error.message.begin(), error.message.end(), kName);
       it != std::sregex_iterator(); ++it) {
    const std::string name = it->str();
    for (auto set = sets.rbegin(); set != sets.rend(); ++set) {
      const std::string key = set->substr(0, set->find('='));
      if (key.size() >= name.size() &&
          key.compare(key.size() - name.size(), name.size(), name) == 0) {
        error.file = "--set " + *set;
        error.line = 0;
        return error;
      }
    }
  }
  return error;
}

int Main(int argc, char** argv) {
  CLI::App app{"gridslam: occupancy-grid graph-SLAM with the distance transform, SURF and SGD"};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", std::string("gridslam ") + GRIDSLAM_VERSION);
  AppContext context;
  bool print_config = false;
  std::string log_level = "info";
  CommonOptions common;
  AddCommonOptions(app, context, log_level, common);
  app.add_flag("--print-config", print_config,
               "Print the effective configuration (defaults + --config + --set) as YAML and exit");

  std::vector<std::pair<CLI::App*, RunFunction>> runners;
  std::vector<CommonOptions> sub_common(Commands().size());
  for (std::size_t k = 0; k < Commands().size(); ++k) {
    const CommandSpec& spec = Commands()[k];
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    sub->fallthrough();
    AddCommonOptions(*sub, context, log_level, sub_common[k]);
    runners.emplace_back(sub, spec.setup(*sub, context));
  }
  if (const auto code = CheckCommandName(argc, argv)) {
    return *code;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  // Log messages go to stderr: stdout carries results (eval's line, --print-config, JSON).
  spdlog::set_default_logger(spdlog::stderr_color_mt("gridslam"));
  spdlog::set_level(spdlog::level::from_str(log_level));
  spdlog::set_pattern("[%l] %v");

  // The YAML file overrides the defaults; flags given on the command line win over both.
  if (!context.config_path.empty()) {
    SlamOptions from_file;
    if (const Status s = io::LoadOptionsFromFile(context.config_path, from_file); !s.ok()) {
      return ReportError(s.error());
    }
    const bool lenient = context.options.log.lenient;
    context.options = from_file;
    context.options.log.lenient = context.options.log.lenient || lenient;
  }
  for (const CommonOptions& c : sub_common) {
    common.rate = c.rate ? c.rate : common.rate;
  }
  if (common.rate) {
    context.options.log.timestamp_rate = *common.rate;
  }
  // --set overrides, in order: the ones before the command name, then those after it.
  std::vector<std::string> sets = common.set;
  for (const CommonOptions& c : sub_common) {
    sets.insert(sets.end(), c.set.begin(), c.set.end());
  }
  for (const std::string& assignment : sets) {
    if (const Status s = io::ApplyOptionOverride(assignment, context.options); !s.ok()) {
      return ReportError(s.error());
    }
  }
  if (const Status s = context.options.Validate(); !s.ok()) {
    return ReportError(AttributeToOverride(s.error(), sets));
  }
  if (print_config) {
    std::cout << "# gridslam effective configuration\n" << io::OptionsToYaml(context.options);
    return kExitOk;
  }
  for (auto& [sub, run] : runners) {
    if (sub->parsed()) {
      return run(context);
    }
  }
  std::cout << app.help();
  return kExitBadInput;
}

}  // namespace
}  // namespace gridslam::app

int main(int argc, char** argv) {
  gridslam::app::ReexecWithHugePages(argv);
  try {
    return gridslam::app::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gridslam: fatal: %s\n", e.what());
    return gridslam::app::kExitRuntimeError;
  }
}
