// The Jacobi eigen-solver: A V = V D with V orthonormal and right-handed, on matrices with known
// spectra (diagonal, repeated eigenvalues, random rotations of a chosen diagonal).
#include <gtest/gtest.h>

#include "support/point_clouds.h"
#include "geometry/symmetric_eigen.h"

using namespace collide;

namespace {

void expectValidDecomposition(const glm::dmat3& a, const SymmetricEigen3& e, double tolerance) {
  const glm::dmat3 v = e.vectors;
  const glm::dmat3 identity = glm::transpose(v) * v;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(identity[i][j], i == j ? 1.0 : 0.0, 1e-12);
  EXPECT_NEAR(glm::determinant(v), 1.0, 1e-12);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 residual = a * v[i] - e.values[i] * v[i];
    EXPECT_LE(glm::length(residual), tolerance) << "eigenpair " << i;
  }
  EXPECT_GE(e.values[0], e.values[1]);
  EXPECT_GE(e.values[1], e.values[2]);
}

}  // namespace

TEST(SymmetricEigen, DiagonalMatrixIsItsOwnSpectrumSortedDescending) {
  const glm::dmat3 a(glm::dvec3(1, 0, 0), glm::dvec3(0, 5, 0), glm::dvec3(0, 0, 3));
  const SymmetricEigen3 e = symmetricEigen(a);
  EXPECT_DOUBLE_EQ(e.values[0], 5.0);
  EXPECT_DOUBLE_EQ(e.values[1], 3.0);
  EXPECT_DOUBLE_EQ(e.values[2], 1.0);
  EXPECT_NEAR(std::abs(e.vectors[0].y), 1.0, 1e-15);
  expectValidDecomposition(a, e, 1e-14);
}

TEST(SymmetricEigen, RotatedDiagonalRecoversEigenvaluesIncludingRepeatedOnes) {
  test::Random random(11);
  for (int trial = 0; trial < 100; ++trial) {
    glm::dvec3 d(random.uniform(-3, 3), random.uniform(-3, 3), random.uniform(-3, 3));
    if (trial % 3 == 0) d.y = d.x;             // a double eigenvalue
    if (trial % 10 == 0) d = glm::dvec3(2.0);  // a multiple of the identity
    // A float rotation is orthogonal only to ~1e-7, which would shift the spectrum by as much:
    // re-orthonormalise it in double so that d is the exact spectrum of a.
    glm::dmat3 r = glm::dmat3(glm::mat3_cast(random.rotation()));
    r[0] = glm::normalize(r[0]);
    r[1] = glm::normalize(r[1] - glm::dot(r[1], r[0]) * r[0]);
    r[2] = glm::cross(r[0], r[1]);
    const glm::dmat3 a = r * glm::dmat3(glm::dvec3(d.x, 0, 0), glm::dvec3(0, d.y, 0), glm::dvec3(0, 0, d.z)) *
                         glm::transpose(r);
    const SymmetricEigen3 e = symmetricEigen(a);
    double sorted[3] = {d.x, d.y, d.z};
    std::sort(sorted, sorted + 3, std::greater<>());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(e.values[i], sorted[i], 1e-12) << "trial " << trial;
    expectValidDecomposition(a, e, 1e-12);
  }
}

TEST(SymmetricEigen, ZeroMatrixGivesZeroesAndABasis) {
  const SymmetricEigen3 e = symmetricEigen(glm::dmat3(0.0));
  EXPECT_EQ(e.values, glm::dvec3(0.0));
  EXPECT_NEAR(glm::determinant(e.vectors), 1.0, 1e-15);
}
