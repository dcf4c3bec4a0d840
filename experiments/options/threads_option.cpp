#include "experiments/options/threads_option.hpp"

#include <string>

#include "core/parallel/parallel_for.hpp"
#include "experiments/options/decimal_integer.hpp"

namespace drape {

CLI::Option* add_threads_option(CLI::App& command, int& threads, const char* default_text) {
  return command
      .add_option("--threads", threads,
                  std::string("threads of a run's force and update loops, 1 to ") +
                      std::to_string(max_threads) + "; results are the same bits for any "
                      "number (default: " + default_text + "; env DRAPELAB_THREADS)")
      ->envname("DRAPELAB_THREADS")
      ->transform(decimal_integer())
      ->check(CLI::Range(1, max_threads));
}

void use_threads(int threads, int fallback) { set_thread_count(threads > 0 ? threads : fallback); }

}  // namespace drape
