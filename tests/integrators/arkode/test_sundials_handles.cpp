// The owners of SUNDIALS objects: an N_Vector that views an Eigen buffer without copying it, read
// back through an Eigen map of the same memory; a Butcher table freed by its handle.
#include "integrators/arkode/sundials_handles.hpp"

#include <gtest/gtest.h>

namespace drape::detail {
namespace {

TEST(SundialsHandles, AWrappedVectorIsTheBufferItself) {
  sundials::Context context;
  Eigen::VectorXd buffer = Eigen::VectorXd::LinSpaced(6, 1.0, 6.0);
  const NVectorHandle v = wrap_vector(buffer, context);
  EXPECT_EQ(N_VGetLength(v.get()), 6);
  EXPECT_EQ(N_VGetArrayPointer(v.get()), buffer.data()) << "no copy";
  N_VScale(2.0, v.get(), v.get());  // a SUNDIALS operation writes the Eigen buffer
  EXPECT_EQ(buffer, Eigen::VectorXd::LinSpaced(6, 2.0, 12.0));
  VecMap map = view(v.get());
  map[0] = -1.0;
  EXPECT_EQ(buffer[0], -1.0);
  EXPECT_EQ(map.size(), 6);
}

TEST(SundialsHandles, ATableHandleOwnsWhatARKODELoads) {
  const ButcherTableHandle table(check_created(
      ARKodeButcherTable_LoadERKByName("ARKODE_HEUN_EULER_2_1_2"), "ARKodeButcherTable_LoadERK"));
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->stages, 2);
  EXPECT_EQ(table->q, 2);
  EXPECT_EQ(table->p, 1);
  // Heun: b = (1/2, 1/2), c = (0, 1).
  EXPECT_EQ(table->b[0], 0.5);
  EXPECT_EQ(table->c[1], 1.0);
}

}  // namespace
}  // namespace drape::detail
