// Eigen-decomposition of a symmetric 3x3 matrix (covariance and inertia tensors), in double.
#pragma once

#include <glm/glm.hpp>

namespace collide {

struct SymmetricEigen3 {
  glm::dvec3 values{0.0};   // descending
  glm::dmat3 vectors{1.0};  // column i is the unit eigenvector of values[i]; a right-handed basis
};

// Cyclic Jacobi rotations (Golub & Van Loan, "Matrix Computations", section 8.5): each rotation zeroes
// one off-diagonal pair; the off-diagonal norm falls quadratically once small, so a few sweeps reach
// double precision. Only the lower triangle's symmetric counterpart is assumed: m must be symmetric.
SymmetricEigen3 symmetricEigen(const glm::dmat3& m);

}  // namespace collide
