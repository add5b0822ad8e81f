#include "rcdem/solver/critical_time_step.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "rcdem/core/rng.hpp"

namespace rcdem {

std::string CriticalTimeStep::how() const {
  if (!converged)
    return fmt::format(
        "2 / omega_max bounded by 2x the stiffest body's own block (Lanczos did not converge in "
        "{} products: a safe bound)",
        operator_applications);
  return fmt::format(
      "2 / omega_max of the assembled system, omega_max {:.5g} rad/s (Lanczos, {} products, "
      "residual {:.1e})",
      omega_max, operator_applications, residual);
}

namespace {

using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

// The largest eigenvalue of the tridiagonal T (diagonal a, off-diagonal b) and the last
// component of its eigenvector: |b_k s_k| is the residual of the Ritz pair (Paige).
std::pair<Real, Real> top_ritz(const std::vector<Real>& a, const std::vector<Real>& b) {
  const auto k = static_cast<Eigen::Index>(a.size());
  Vector diag = Eigen::Map<const Vector>(a.data(), k);
  Vector sub = Eigen::Map<const Vector>(b.data(), std::max<Eigen::Index>(k - 1, 0));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>> t;
  t.computeFromTridiagonal(diag, sub, Eigen::ComputeEigenvectors);
  return {t.eigenvalues()[k - 1], t.eigenvectors()(k - 1, k - 1)};
}

}  // namespace

// The Lanczos recurrence without reorthogonalisation: three vectors of memory. Lost orthogonality
// only repeats Ritz values already found (Paige), it never puts one above lambda_max, so the top
// Ritz value is a lower bound that rises to lambda_max. A breakdown (beta ~ 0) means the Krylov
// space is invariant; from a random start it holds the top eigenvector, so the value is exact.
// Written here rather than taken from Spectra (SymEigsSolver 1.0.1): on a rank-deficient operator
// (tests/verification/test_critical_time_step.cpp, two bodies and one rotational spring) Spectra
// reported convergence to 1.25e10 where the eigenvalue is 9.52e9 (residual 0.30).
CriticalTimeStep assembled_critical_time_step(const AssembledStiffness& k, Real lambda_block,
                                              Real tolerance) {
  CriticalTimeStep out;
  const Eigen::Index n = k.size();
  Rng rng(20261124);
  Vector q(n), q_prev = Vector::Zero(n), w(n);
  for (Eigen::Index i = 0; i < n; ++i) q[i] = rng.uniform(-1.0, 1.0);
  q /= q.norm();
  std::vector<Real> alpha, beta;
  Real lambda = 0.0, beta_prev = 0.0;
  constexpr int kMaxProducts = 2000;
  for (int j = 0; j < std::min<Eigen::Index>(kMaxProducts, n); ++j) {
    k.apply(q.data(), w.data());
    ++out.operator_applications;
    w -= beta_prev * q_prev;
    const Real a = q.dot(w);
    w -= a * q;
    const Real b = w.norm();
    alpha.push_back(a);
    const auto [theta, last] = top_ritz(alpha, beta);
    lambda = theta;
    out.residual = theta > 0.0 ? std::abs(b * last) / theta : 0.0;
    // Converged, or the Krylov space is invariant (the value is then exact).
    if (theta > 0.0 && (out.residual <= tolerance || b <= 1e-14 * theta)) {
      out.converged = true;
      break;
    }
    beta.push_back(b);
    q_prev = q;
    q = w / b;
    beta_prev = b;
  }
  if (!out.converged) lambda = 2.0 * lambda_block;
  lambda = std::max(lambda, lambda_block);
  out.omega_max = std::sqrt(lambda);
  out.time_step = 2.0 / out.omega_max;
  return out;
}

}  // namespace rcdem
