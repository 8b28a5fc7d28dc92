// Thin logging shim over spdlog (docs/style.md §10). The library logs through these macros and
// never configures sinks or levels; the apps do. No logging inside per-beam or per-cell loops.
#pragma once

#include <spdlog/spdlog.h>

#define GRIDSLAM_LOG_TRACE(...) ::spdlog::trace(__VA_ARGS__)
#define GRIDSLAM_LOG_DEBUG(...) ::spdlog::debug(__VA_ARGS__)
#define GRIDSLAM_LOG_INFO(...) ::spdlog::info(__VA_ARGS__)
#define GRIDSLAM_LOG_WARN(...) ::spdlog::warn(__VA_ARGS__)
#define GRIDSLAM_LOG_ERROR(...) ::spdlog::error(__VA_ARGS__)
