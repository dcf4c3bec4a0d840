#include "experiments/sweep/deliberate_crash.hpp"

#include <csignal>
#include <cstdlib>

namespace drape {

void crash_if_asked_for_test(const std::string& run_id) {
  const char* value = std::getenv("DRAPELAB_TEST_CRASH");
  if (value == nullptr) return;
  const std::string request = value;
  const auto colon = request.find(':');
  const std::string kind = request.substr(0, colon);
  if (colon != std::string::npos && run_id.find(request.substr(colon + 1)) == std::string::npos)
    return;
  if (kind == "abort") std::abort();
  if (kind == "segv") {
    // The default action, not a sanitizer's handler, so the parent sees signal 11 in every build.
    std::signal(SIGSEGV, SIG_DFL);
    std::raise(SIGSEGV);
  }
}

}  // namespace drape
