#include "app_huge_pages.hpp"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <unistd.h>

namespace gridslam::app {
namespace {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define GRIDSLAM_UNDER_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define GRIDSLAM_UNDER_SANITIZER 1
#endif

#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35)) && \
    !defined(GRIDSLAM_UNDER_SANITIZER)
constexpr bool kSupported = true;
#else
constexpr bool kSupported = false;
#endif

// The kernel gives transparent huge pages to the memory that asks for them, and only to it.
bool KernelGivesHugePagesOnRequest() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string setting;
  std::getline(file, setting);
  return setting.find("[madvise]") != std::string::npos;
}

}  // namespace

void ReexecWithHugePages(char** argv) {
  if (!kSupported || std::getenv("GLIBC_TUNABLES") != nullptr) {
    return;
  }
  const char* wanted = std::getenv("GRIDSLAM_HUGE_PAGES");
  if (wanted != nullptr && std::strcmp(wanted, "0") == 0) {
    return;
  }
  // valgrind preloads its own libraries and follows no exec by default.
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload != nullptr && std::strstr(preload, "vgpreload") != nullptr) {
    return;
  }
  if (!KernelGivesHugePagesOnRequest()) {
    return;
  }
  if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) != 0) {
    return;
  }
  execv("/proc/self/exe", argv);
  unsetenv("GLIBC_TUNABLES");  // exec failed: carry on as we are
}

}  // namespace gridslam::app
