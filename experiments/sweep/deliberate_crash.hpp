#pragma once
// A deliberate crash of an experiment's run, for the tests of run isolation only
// (docs/experiments.md, "Isolation"). Nothing happens unless DRAPELAB_TEST_CRASH is set.
#include <string>

namespace drape {

/// Crashes the calling process when the environment asks for it: DRAPELAB_TEST_CRASH=abort or
/// segv crashes every run, abort:ID or segv:ID only the run whose id contains ID. Test-only.
void crash_if_asked_for_test(const std::string& run_id);

}  // namespace drape
