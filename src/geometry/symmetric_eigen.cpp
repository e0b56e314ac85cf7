// Symmetric 3x3 eigen-solver by cyclic Jacobi rotations (Golub & Van Loan, section 8.5). Chosen over
// the closed-form cubic because it stays accurate for repeated eigenvalues (a ring of points, a
// cube), where the cubic's eigenvectors come out of a near-singular system.
#include "geometry/symmetric_eigen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace collide {

SymmetricEigen3 symmetricEigen(const glm::dmat3& m) {
  // a[row][col], so that the textbook indices read as written; glm is column-major.
  double a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = 0.5 * (m[c][r] + m[r][c]);
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  double scale = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) scale = std::max(scale, std::abs(a[r][c]));

  if (scale > 0.0) {
    for (int sweep = 0; sweep < 50; ++sweep) {
      const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
      if (off <= 1e-30 * scale * scale) break;
      for (int p = 0; p < 2; ++p) {
        for (int q = p + 1; q < 3; ++q) {
          if (a[p][q] == 0.0) continue;
          // The rotation (c, s) in the (p, q) plane that zeroes a[p][q]; t is the smaller root of
          // t^2 + 2 theta t - 1 = 0, which keeps the rotation angle below pi/4 (stable).
          const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
          const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
          const double c = 1.0 / std::sqrt(t * t + 1.0);
          const double s = t * c;
          for (int k = 0; k < 3; ++k) {  // A <- A J
            const double akp = a[k][p], akq = a[k][q];
            a[k][p] = c * akp - s * akq;
            a[k][q] = s * akp + c * akq;
          }
          for (int k = 0; k < 3; ++k) {  // A <- J^T A
            const double apk = a[p][k], aqk = a[q][k];
            a[p][k] = c * apk - s * aqk;
            a[q][k] = s * apk + c * aqk;
          }
          for (int k = 0; k < 3; ++k) {  // V <- V J
            const double vkp = v[k][p], vkq = v[k][q];
            v[k][p] = c * vkp - s * vkq;
            v[k][q] = s * vkp + c * vkq;
          }
        }
      }
    }
  }

  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
  SymmetricEigen3 result;
  for (int i = 0; i < 3; ++i) {
    result.values[i] = a[order[i]][order[i]];
    result.vectors[i] = glm::normalize(glm::dvec3(v[0][order[i]], v[1][order[i]], v[2][order[i]]));
  }
  // Right-handed, so that the basis is a rotation.
  result.vectors[2] = glm::normalize(glm::cross(result.vectors[0], result.vectors[1]));
  return result;
}

}  // namespace collide
