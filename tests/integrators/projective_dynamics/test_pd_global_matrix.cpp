// The global step's matrix of Projective Dynamics (docs/integrators/projective-dynamics.md):
// A = d I + sum_e (k_e + c) a_e a_e^T + w diag(contact) over the free particles, assembled here
// densely from its definition and solved with Eigen's dense LDLT as the reference.
#include "integrators/projective_dynamics/pd_global_matrix.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "tests/support/test_support.hpp"

namespace drape {
namespace {

constexpr double kContactWeight = 40.0;

/// A from its definition: rows of the free particles in ascending order.
Eigen::MatrixXd dense_a(const SpringList& springs, const std::vector<unsigned char>& fixed,
                        const std::vector<unsigned char>& contact, double diagonal, double extra) {
  std::vector<int> row(fixed.size(), -1);
  int rows = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (!fixed[i]) row[i] = rows++;
  Eigen::MatrixXd a = diagonal * Eigen::MatrixXd::Identity(rows, rows);
  for (Eigen::Index e = 0; e < springs.size(); ++e) {
    Eigen::VectorXd incidence = Eigen::VectorXd::Zero(rows);
    if (row[springs.first[e]] >= 0) incidence[row[springs.first[e]]] = 1.0;
    if (row[springs.second[e]] >= 0) incidence[row[springs.second[e]]] = -1.0;
    a += (springs.stiffness[e] + extra) * incidence * incidence.transpose();
  }
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (row[i] >= 0 && contact[i]) a(row[i], row[i]) += kContactWeight;
  return a;
}

/// A^-1 B through solve_in_place: B's rows (free particles ascending) moved to slot order and back.
Eigen::MatrixXd solved(const PdGlobalMatrix& matrix, const std::vector<unsigned char>& fixed,
                       const Eigen::MatrixXd& b) {
  std::vector<int> row(fixed.size(), -1);
  int rows = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (!fixed[i]) row[i] = rows++;
  std::vector<double> z(3 * static_cast<std::size_t>(matrix.num_free()));
  for (int s = 0; s < matrix.num_free(); ++s)
    for (int c = 0; c < 3; ++c) z[3 * s + c] = b(row[matrix.slots()[s]], c);
  matrix.solve_in_place(z.data());
  Eigen::MatrixXd x(b.rows(), 3);
  for (int s = 0; s < matrix.num_free(); ++s)
    for (int c = 0; c < 3; ++c) x(row[matrix.slots()[s]], c) = z[3 * s + c];
  return x;
}

struct Grid {
  Cloth cloth = build_cloth(testing::small_cloth(4, 5));
  std::vector<unsigned char> fixed = std::vector<unsigned char>(20, 0);
  std::vector<unsigned char> contact = std::vector<unsigned char>(20, 0);
  Grid() {
    fixed[0] = fixed[4] = fixed[13] = 1;  // two corners and an inner particle
    contact[7] = contact[13] = contact[18] = 1;  // 13 is fixed: its contact adds nothing
  }
};

TEST(PdGlobalMatrix, SolvesTheMatrixOfItsDefinition) {
  const Grid g;
  PdGlobalMatrix matrix(g.cloth.springs, kContactWeight);
  const double diagonal = 0.001 / (0.01 * 0.01) + 0.02 / 0.01, extra = 0.5 / 0.01;
  matrix.factor(g.fixed, g.contact, diagonal, extra);
  ASSERT_EQ(matrix.num_free(), 17);
  std::vector<int> slots = matrix.slots();
  std::sort(slots.begin(), slots.end());
  std::vector<int> free;
  for (int i = 0; i < 20; ++i)
    if (!g.fixed[i]) free.push_back(i);
  EXPECT_EQ(slots, free) << "every free particle has one slot";
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(17, 3);
  const Eigen::MatrixXd a = dense_a(g.cloth.springs, g.fixed, g.contact, diagonal, extra);
  const Eigen::MatrixXd expected = a.ldlt().solve(b);
  EXPECT_LT((solved(matrix, g.fixed, b) - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((a * solved(matrix, g.fixed, b) - b).norm(), 1e-10 * b.norm());
}

TEST(PdGlobalMatrix, RefactoringTakesTheNewContactFlags) {
  Grid g;
  PdGlobalMatrix matrix(g.cloth.springs, kContactWeight);
  matrix.factor(g.fixed, g.contact, 10.0, 0.0);
  std::vector<unsigned char> contact(20, 0);
  contact[1] = contact[2] = contact[19] = 1;
  matrix.refactor(contact);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(17, 3);
  const Eigen::MatrixXd expected = dense_a(g.cloth.springs, g.fixed, contact, 10.0, 0.0).ldlt().solve(b);
  EXPECT_LT((solved(matrix, g.fixed, b) - expected).norm(), 1e-12 * expected.norm());
}

// With no springs A is diagonal: the solve divides by d, or by d + w in contact.
TEST(PdGlobalMatrix, WithoutSpringsTheSolveIsADivision) {
  SpringList none;
  PdGlobalMatrix matrix(none, kContactWeight);
  matrix.factor({0, 1, 0}, {1, 0, 0}, 4.0, 0.0);
  ASSERT_EQ(matrix.num_free(), 2);
  const Eigen::MatrixXd b = (Eigen::MatrixXd(2, 3) << 8.0, 12.0, 88.0, 4.0, 8.0, 12.0).finished();
  const Eigen::MatrixXd x = solved(matrix, {0, 1, 0}, b);
  EXPECT_DOUBLE_EQ(x(0, 0), 8.0 / 44.0) << "particle 0 in contact: d + w";
  EXPECT_DOUBLE_EQ(x(0, 2), 88.0 / 44.0);
  EXPECT_DOUBLE_EQ(x(1, 1), 8.0 / 4.0) << "particle 2: d";
}

TEST(PdGlobalMatrix, EveryParticleFixedLeavesNothingToSolve) {
  const Grid g;
  PdGlobalMatrix matrix(g.cloth.springs, kContactWeight);
  matrix.factor(std::vector<unsigned char>(20, 1), g.contact, 1.0, 0.0);
  EXPECT_EQ(matrix.num_free(), 0);
  EXPECT_TRUE(matrix.slots().empty());
  matrix.solve_in_place(nullptr);
}

}  // namespace
}  // namespace drape
