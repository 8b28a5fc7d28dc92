// gridslam: 2D laser graph-SLAM from the command line (DESIGN.md §2).
#include <cstdio>
#include <exception>
#include <iostream>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "gridslam/io/options_yaml.hpp"

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

int Main(int argc, char** argv) {
  CLI::App app{"gridslam: occupancy-grid graph-SLAM with the distance transform, SURF and SGD"};
  app.require_subcommand(0, 1);
  AppContext context;
  bool print_config = false;
  std::string log_level = "info";
  app.add_option("--config", context.config_path, "YAML configuration overriding the defaults")
      ->check(CLI::ExistingFile);
  app.add_flag("--print-config", print_config,
               "Print the effective configuration (defaults + --config) as YAML and exit");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.add_flag("--lenient", context.options.log.lenient,
               "Skip and count malformed log lines instead of failing");
  app.add_option("--scan-topic", context.bag.scan_topic,
                 "Bags: sensor_msgs/LaserScan topic (default: the only one)");
  app.add_option("--odom-topic", context.bag.odom_topic,
                 "Bags: nav_msgs/Odometry topic (default: the only one, else TF odom->base_link)");
  app.add_option("--odom-frame", context.bag.odom_frame,
                 "Bags: odometry from TF with this odometry frame (default odom)");
  app.add_option("--base-frame", context.bag.base_frame,
                 "Bags: robot frame (default: the odometry's child frame, else base_link)");

  std::vector<std::pair<CLI::App*, RunFunction>> runners;
  for (auto& spec : Commands()) {
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    sub->fallthrough();
    runners.emplace_back(sub, spec.setup(*sub, context));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
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
  if (const Status s = context.options.Validate(); !s.ok()) {
    return ReportError(s.error());
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
  try {
    return gridslam::app::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gridslam: fatal: %s\n", e.what());
    return gridslam::app::kExitRuntimeError;
  }
}
