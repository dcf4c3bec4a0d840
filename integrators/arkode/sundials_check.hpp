#pragma once
// Every SUNDIALS call goes through one helper: a negative return flag becomes an
// IntegratorFailure carrying ARKODE's flag name, so that the runner reports a failed run
// (status "failed", exit 3) instead of the program aborting.
#include <arkode/arkode_arkstep.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "integrators/interface/integrator.hpp"

namespace drape::detail {

/// Which ARKODE function names the flag: the integrator's own, or its linear-solver interface.
using FlagNamer = char* (*)(long int);

/// Throws IntegratorFailure(flag name, "<call> failed ...: <detail>") when `flag` < 0; returns
/// `flag` otherwise (positive flags such as ARK_TSTOP_RETURN are successes). `detail` is
/// ARKODE's own explanation, when it gave one.
inline int check_sundials(int flag, const char* call, FlagNamer namer = ARKStepGetReturnFlagName,
                          const std::string& detail = "") {
  if (flag >= 0) return flag;
  // ARKODE allocates the name with malloc and leaves it to the caller to free.
  const std::unique_ptr<char, decltype(&std::free)> name(namer(flag), &std::free);
  const std::string flag_name = name ? name.get() : "flag " + std::to_string(flag);
  throw IntegratorFailure(flag_name, std::string(call) + " failed with " + flag_name + " (" +
                                         std::to_string(flag) + ")" +
                                         (detail.empty() ? "" : ": " + detail));
}

/// Throws IntegratorFailure("ARK_MEM_FAIL") when a SUNDIALS constructor returned null.
template <class Pointer>
Pointer check_created(Pointer object, const char* call) {
  if (!object)
    throw IntegratorFailure("ARK_MEM_FAIL", std::string(call) + " could not create its object");
  return object;
}

}  // namespace drape::detail
