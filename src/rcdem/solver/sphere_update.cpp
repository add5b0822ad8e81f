#include "rcdem/solver/sphere_update.hpp"

#include <cmath>

#include "rcdem/core/simd_level.hpp"
#include "rcdem/core/small_angle.hpp"

namespace rcdem {

namespace {

[[gnu::always_inline]] inline void sphere_update_lanes(Bodies& b, Index begin, Index end, Real dt,
                                                       Real damping, const SphereStepOutputs& out) {
  // Raw components: Vec3 is 3 doubles, Eigen's quaternion 4 (x, y, z, w).
  // From the block's first body: the lanes index from 0.
  Real* x = b.position[begin].data();
  Real* v = b.velocity[begin].data();
  Real* w = b.angular_velocity[begin].data();
  Real* ang = b.angular_momentum[begin].data();
  Real* q = b.orientation[begin].coeffs().data();
  const Real* f = b.force[begin].data();
  const Real* t = b.torque[begin].data();
  const Real* inertia = b.inertia[begin].data();
  const Real* mass = b.mass.data() + begin;
  const Real* radius = b.radius.data() + begin;
  Real* damping_work_out = out.damping_work + begin;
  Real* kinetic_out = out.kinetic + begin;
  std::int64_t* jumped_out = out.jumped + begin;
  static_assert(0.25 * kStableTurnLimit * kStableTurnLimit < 1e-2,
                "the series must cover a stable turn");
#pragma omp simd
  for (Index i = 0; i < end - begin; ++i) {
    const Real inv_m = dt / mass[i];
    const Real inertia_i = inertia[3 * i];
    Real v_new[3], w_new[3], l_old[3], l_new[3], dx[3];
    Real damping_work = 0, v_dot = 0, lw = 0, dx_sq = 0, w_sq = 0;
    for (int k = 0; k < 3; ++k) {
      const Real v_old = v[3 * i + k], w_old = w[3 * i + k];
      const Real fd = cundall_damping(damping, f[3 * i + k], v_old);
      const Real td = cundall_damping(damping, t[3 * i + k], w_old);
      v_new[k] = v_old + (f[3 * i + k] - fd) * inv_m;
      // Spheres keep w as their state: L = I w, then L += T dt, w = L / I (rigid_rotation.hpp).
      l_old[k] = inertia_i * w_old;
      l_new[k] = l_old[k] + (t[3 * i + k] - td) * dt;
      w_new[k] = l_new[k] / inertia_i;
      damping_work += fd * (0.5 * (v_old + v_new[k])) * dt + td * (0.5 * (w_old + w_new[k])) * dt;
      v_dot += v_old * v_new[k];
      lw += l_old[k] * w_new[k] + l_new[k] * w_old;
      dx[k] = v_new[k] * dt;
      dx_sq += dx[k] * dx[k];
      w_sq += w_new[k] * w_new[k];
    }
    damping_work_out[i] = damping_work;
    kinetic_out[i] = 0.5 * mass[i] * v_dot + 0.25 * lw;
    for (int k = 0; k < 3; ++k) {
      v[3 * i + k] = v_new[k];
      w[3 * i + k] = w_new[k];
      ang[3 * i + k] = l_new[k];
      x[3 * i + k] += dx[k];
    }
    // q <- exp(w dt) q (rigid_rotation.hpp, rotation_exp), then renormalised. The series holds for
    // every turn below 0.2 rad (h < 0.1): beyond the 0.05 rad of the check below, so a body it
    // would not hold for stops the run.
    const Real h2 = 0.25 * w_sq * dt * dt;
    Real c, sinc;
    small_angle_cos_sinc(h2, c, sinc);
    const Real s = 0.5 * sinc * dt;  // sin(h) / |w|
    const Real ex = s * w_new[0], ey = s * w_new[1], ez = s * w_new[2];
    const Real qx = q[4 * i], qy = q[4 * i + 1], qz = q[4 * i + 2], qw = q[4 * i + 3];
    Real nw = c * qw - ex * qx - ey * qy - ez * qz;
    Real nx = c * qx + ex * qw + ey * qz - ez * qy;
    Real ny = c * qy + ey * qw + ez * qx - ex * qz;
    Real nz = c * qz + ez * qw + ex * qy - ey * qx;
    const Real inv_norm = 1.0 / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
    q[4 * i] = nx * inv_norm;
    q[4 * i + 1] = ny * inv_norm;
    q[4 * i + 2] = nz * inv_norm;
    q[4 * i + 3] = nw * inv_norm;
    // Instability: in a stable run nothing moves a twentieth of its size or turns 0.05 rad in
    // one step (a NaN fails both).
    const Real dx_limit = 0.05 * radius[i];
    jumped_out[i] =
        !(dx_sq < dx_limit * dx_limit) | !(w_sq * dt * dt < kStableTurnLimit * kStableTurnLimit);
  }
}

void sphere_update_lanes_baseline(Bodies& b, Index begin, Index end, Real dt, Real damping,
                                  const SphereStepOutputs& out) {
  sphere_update_lanes(b, begin, end, dt, damping, out);
}
#if RCDEM_SIMD_MULTIVERSION
RCDEM_SIMD_TARGET_AVX2 void sphere_update_lanes_avx2(Bodies& b, Index begin, Index end, Real dt,
                                                     Real damping, const SphereStepOutputs& out) {
  sphere_update_lanes(b, begin, end, dt, damping, out);
}
RCDEM_SIMD_TARGET_AVX512 void sphere_update_lanes_avx512(Bodies& b, Index begin, Index end, Real dt,
                                                         Real damping,
                                                         const SphereStepOutputs& out) {
  sphere_update_lanes(b, begin, end, dt, damping, out);
}
#endif

}  // namespace

void advance_spheres(Bodies& b, Index begin, Index end, Real dt, Real damping,
                     const SphereStepOutputs& out) {
#if RCDEM_SIMD_MULTIVERSION
  switch (simd_level()) {
    case SimdLevel::Avx512:
      return sphere_update_lanes_avx512(b, begin, end, dt, damping, out);
    case SimdLevel::Avx2:
      return sphere_update_lanes_avx2(b, begin, end, dt, damping, out);
    case SimdLevel::Baseline:
      break;
  }
#endif
  sphere_update_lanes_baseline(b, begin, end, dt, damping, out);
}

}  // namespace rcdem
