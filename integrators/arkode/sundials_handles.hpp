#pragma once
// Owners of SUNDIALS objects: each is released exactly once by its destructor, including when a
// setup call throws half-way.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.hpp>
#include <sundials/sundials_linearsolver.h>

#include <Eigen/Core>
#include <memory>

#include "integrators/arkode/sundials_check.hpp"

namespace drape::detail {

struct NVectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct ArkodeDeleter {
  void operator()(void* memory) const { ARKStepFree(&memory); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver solver) const { SUNLinSolFree(solver); }
};
struct ButcherTableDeleter {
  void operator()(ARKodeButcherTable table) const { ARKodeButcherTable_Free(table); }
};

/// A serial N_Vector.
using NVectorHandle = std::unique_ptr<std::remove_pointer_t<N_Vector>, NVectorDeleter>;
/// ARKStep memory.
using ArkodeHandle = std::unique_ptr<void, ArkodeDeleter>;
/// A SUNDIALS linear solver.
using LinearSolverHandle =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
/// A Butcher table loaded from ARKODE's built-in list.
using ButcherTableHandle =
    std::unique_ptr<std::remove_pointer_t<ARKodeButcherTable>, ButcherTableDeleter>;

/// An N_Vector that views `buffer` (no copy): the buffer must outlive it and never reallocate.
inline NVectorHandle wrap_vector(Eigen::VectorXd& buffer, SUNContext context) {
  return NVectorHandle(check_created(
      N_VMake_Serial(static_cast<sunindextype>(buffer.size()), buffer.data(), context),
      "N_VMake_Serial"));
}

/// The data of a serial N_Vector as an Eigen map.
inline VecMap view(N_Vector v) {
  return VecMap(N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v)));
}

}  // namespace drape::detail
