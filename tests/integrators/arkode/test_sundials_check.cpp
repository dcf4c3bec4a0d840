// Every SUNDIALS call's flag: a negative one an IntegratorFailure named by ARKODE's own flag name
// (a failed run, status "failed"), a positive one a success passed through, a null object
// ARK_MEM_FAIL.
#include "integrators/arkode/sundials_check.hpp"

#include <gtest/gtest.h>

namespace drape::detail {
namespace {

std::string failure(int flag, const std::string& detail = "") {
  try {
    check_sundials(flag, "ARKStepEvolve", ARKStepGetReturnFlagName, detail);
  } catch (const IntegratorFailure& e) {
    return e.flag() + " | " + e.what();
  }
  return "no failure";
}

TEST(SundialsCheck, NegativeFlagsFailWithArkodesName) {
  EXPECT_EQ(failure(ARK_CONV_FAILURE),
            "ARK_CONV_FAILURE | ARKStepEvolve failed with ARK_CONV_FAILURE (" +
                std::to_string(ARK_CONV_FAILURE) + ")");
  EXPECT_EQ(failure(ARK_TOO_MUCH_WORK, "t = 0.5"),
            "ARK_TOO_MUCH_WORK | ARKStepEvolve failed with ARK_TOO_MUCH_WORK (" +
                std::to_string(ARK_TOO_MUCH_WORK) + "): t = 0.5");
}

TEST(SundialsCheck, SuccessFlagsPassThrough) {
  EXPECT_EQ(check_sundials(ARK_SUCCESS, "ARKStepEvolve"), ARK_SUCCESS);
  EXPECT_EQ(check_sundials(ARK_TSTOP_RETURN, "ARKStepEvolve"), ARK_TSTOP_RETURN);
}

TEST(SundialsCheck, ANullObjectIsAMemoryFailure) {
  int object = 0;
  EXPECT_EQ(check_created(&object, "N_VNew_Serial"), &object);
  try {
    check_created(static_cast<int*>(nullptr), "N_VNew_Serial");
    FAIL() << "no failure";
  } catch (const IntegratorFailure& e) {
    EXPECT_EQ(e.flag(), "ARK_MEM_FAIL");
    EXPECT_STREQ(e.what(), "N_VNew_Serial could not create its object");
  }
}

}  // namespace
}  // namespace drape::detail
