// First two moments of a point set and the plane fit computed from them (paper Section 3.1).
#ifndef FOGNAV_PERCEPTION_INTERNAL_PLANE_MOMENTS_H_
#define FOGNAV_PERCEPTION_INTERNAL_PLANE_MOMENTS_H_

#include <cmath>

#include <Eigen/Core>

namespace fognav::perception::internal {

// N, b = sum p and A = sum p p^T of a point set (eq. 5); adding and subtracting sets is
// constant time (eq. 7).
struct Moments {
  int n = 0;
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();

  void Add(const Eigen::Vector3d& p) {
    ++n;
    b += p;
    A.noalias() += p * p.transpose();
  }
  void Subtract(const Eigen::Vector3d& p) {
    --n;
    b -= p;
    A.noalias() -= p * p.transpose();
  }
  // eq. (7): A <- A + N E(pp^T), b <- b + N E(p).
  void Add(const Moments& o) {
    n += o.n;
    b += o.b;
    A += o.A;
  }
  void Subtract(const Moments& o) {
    n -= o.n;
    b -= o.b;
    A -= o.A;
  }
};

// A plane p . n = dist with unit normal n; ok is false when the moments do not define one.
struct PlaneFit {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double dist = 0;
  bool ok = false;
};

// eq. (3)-(6): solves A m = b by Cramer's rule, n = m / |m|, d = 1 / |m|, then flips the sign of
// both so that n points towards the camera at the origin (then d < 0; eq. (9) is unchanged).
inline PlaneFit FitPlane(const Moments& m) {
  PlaneFit fit;
  if (m.n < 3) return fit;
  const Eigen::Matrix3d& A = m.A;
  // cofactors of the symmetric A
  const double c00 = A(1, 1) * A(2, 2) - A(1, 2) * A(1, 2);
  const double c01 = A(0, 2) * A(1, 2) - A(0, 1) * A(2, 2);
  const double c02 = A(0, 1) * A(1, 2) - A(0, 2) * A(1, 1);
  const double c11 = A(0, 0) * A(2, 2) - A(0, 2) * A(0, 2);
  const double c12 = A(0, 1) * A(0, 2) - A(0, 0) * A(1, 2);
  const double c22 = A(0, 0) * A(1, 1) - A(0, 1) * A(0, 1);
  const double det = A(0, 0) * c00 + A(0, 1) * c01 + A(0, 2) * c02;
  const double trace = A.trace();
  if (!(std::abs(det) > 1e-18 * trace * trace * trace)) return fit;
  // m = adj(A) b / det, up to the positive factor 1/|det| that the normalisation removes
  Eigen::Vector3d mv(c00 * m.b.x() + c01 * m.b.y() + c02 * m.b.z(),
                     c01 * m.b.x() + c11 * m.b.y() + c12 * m.b.z(),
                     c02 * m.b.x() + c12 * m.b.y() + c22 * m.b.z());
  mv /= det;
  const double len = mv.norm();
  if (!(len > 0) || !std::isfinite(len)) return fit;
  fit.n = -mv / len;
  fit.dist = -1.0 / len;
  fit.ok = true;
  return fit;
}

// eq. (9): mean squared residual of the moments' points to plane (n, d), clamped at zero.
inline double MeanSquaredResidual(const Moments& m, const Eigen::Vector3d& n, double d) {
  if (m.n <= 0) return 0;
  const double v = (n.dot(m.A * n) - 2 * d * n.dot(m.b)) / m.n + d * d;
  return v > 0 ? v : 0;
}

// eq. (9): RMS residual of the moments' points to plane (n, d).
inline double Rms(const Moments& m, const Eigen::Vector3d& n, double d) {
  return std::sqrt(MeanSquaredResidual(m, n, d));
}

// eq. (10): r_sigma = rms / sigma.
inline double RSigma(const Moments& m, const Eigen::Vector3d& n, double d, double sigma) {
  return Rms(m, n, d) / sigma;
}

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_PLANE_MOMENTS_H_
