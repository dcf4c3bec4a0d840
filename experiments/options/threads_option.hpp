#pragma once
// --threads N of `run`, `live` and `experiment`, or the environment's DRAPELAB_THREADS: how many
// threads a run's hot loops use (core/parallel, docs/performance/threads.md).
#include <CLI/CLI.hpp>

namespace drape {

/// More threads than this is a typo or an overflow, not a machine.
inline constexpr int max_threads = 1024;

/// Adds --threads to `command` (a decimal integer in 1 .. max_threads, also read from
/// DRAPELAB_THREADS when the flag is absent; a bad value is exit 2 naming --threads); `threads`
/// stays 0 when neither is given.
CLI::Option* add_threads_option(CLI::App& command, int& threads, const char* default_text);

/// Sets the hot loops' thread count of this process: `threads` when given (> 0), otherwise
/// `fallback`.
void use_threads(int threads, int fallback);

}  // namespace drape
