// Command registry of the `gridslam` program (docs/design.md §2). Each subcommand lives in its own
// cmd_<name>.cpp and registers itself at start-up with GRIDSLAM_REGISTER_COMMAND; main() parses
// argv with CLI11, loads the configuration, and runs the chosen subcommand. Only apps/ knows
// argv and file paths; the library takes option structs.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "gridslam/common/result.hpp"
#include "gridslam/pipeline/slam_options.hpp"
#include "gridslam/recording/recording_reader.hpp"

namespace gridslam::app {

/// What every subcommand gets when it runs.
struct AppContext {
  SlamOptions options;        ///< Defaults, overridden by --config and command-line flags.
  std::string config_path;    ///< The --config file, if any.
  recording::BagOptions bag;  ///< --scan-topic, --odom-topic, --odom-frame, --base-frame.

  /// How recordings (CARMEN logs and bags) are read.
  [[nodiscard]] recording::RecordingOptions Recording() const { return {options.log, bag}; }
};

/// Exit codes (docs/design.md §2).
constexpr int kExitOk = 0;
constexpr int kExitRuntimeError = 1;
constexpr int kExitBadInput = 2;

/// Prints an error and returns its exit code (2 for bad input, 1 otherwise).
int ReportError(const Error& error);

/// CLI11 check of an output folder (`-o DIR`): it may not exist yet, but neither it nor its
/// nearest existing ancestor may be something other than a folder (a usage error, exit 2).
inline CLI::Validator OutputFolder() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        std::error_code ec;
        for (std::filesystem::path p(value); !p.empty(); p = p.parent_path()) {
          if (std::filesystem::exists(p, ec)) {
            if (!std::filesystem::is_directory(p, ec)) {
              return "not a folder: " + p.string();
            }
            return {};
          }
          if (p == p.parent_path()) {
            break;
          }
        }
        return {};
      },
      "DIR");
}

/// A subcommand: `setup` adds the subcommand's options to `sub` and returns the function that
/// runs it once parsing and configuration are done.
using RunFunction = std::function<int(AppContext&)>;
struct CommandSpec {
  std::string name;
  std::string description;
  std::function<RunFunction(CLI::App& sub, AppContext& context)> setup;
};

/// Adds a command to the registry; returns a dummy so it can initialize a static.
int RegisterCommand(CommandSpec spec);
std::vector<CommandSpec>& Commands();

}  // namespace gridslam::app

#define GRIDSLAM_CONCAT_INNER(a, b) a##b
#define GRIDSLAM_CONCAT(a, b) GRIDSLAM_CONCAT_INNER(a, b)
#define GRIDSLAM_REGISTER_COMMAND(...)                                       \
  static const int GRIDSLAM_CONCAT(gridslam_command_registered_, __LINE__) = \
      ::gridslam::app::RegisterCommand(__VA_ARGS__)
