#include "rcdem/solver/assembled_stiffness.hpp"

#include <algorithm>
#include <cmath>

#include "rcdem/core/parallel.hpp"

namespace rcdem {

AssembledStiffness::AssembledStiffness(const Bodies& b)
    : bodies_(b.size()), centre0_(b.position0.begin(), b.position0.begin() + b.size()) {
  const auto n = static_cast<std::size_t>(bodies_);
  inv_sqrt_mass_.resize(n);
  inv_sqrt_inertia_.resize(n);
  for (Index i = 0; i < bodies_; ++i) {
    inv_sqrt_mass_[static_cast<std::size_t>(i)] = 1.0 / std::sqrt(b.mass[i]);
    const Mat3 q = b.orientation0[i].toRotationMatrix();
    inv_sqrt_inertia_[static_cast<std::size_t>(i)] =
        q * b.inertia[i].cwiseSqrt().cwiseInverse().asDiagonal() * q.transpose();
  }
  zt_.resize(n);
  zr_.resize(n);
  body_force_.resize(n);
  body_moment_.resize(n);
}

void AssembledStiffness::add_network(const ContactNetwork& net, std::vector<Vec3> normal) {
  const auto contacts = static_cast<std::size_t>(net.contact_count());
  if (contact_force_.size() < contacts) {
    contact_force_.resize(contacts);
    contact_moment_a_.resize(contacts);
    contact_moment_b_.resize(contacts);
  }
  networks_.push_back({&net, std::move(normal), BodyContacts::build(net, bodies_)});
}

void AssembledStiffness::add_spring(Index a, Index b, const Vec3& arm_a, const Vec3& arm_b,
                                    const Vec3& n, Real kn, Real ks) {
  springs_.push_back({a, b, arm_a, arm_b, n, kn, ks});
}

void AssembledStiffness::add_rotational(Index a, Index b, const Mat3& k) {
  rotational_.push_back({a, b, k});
}

namespace {
// S u for S = k_n n n^T + k_s (I - n n^T).
inline Vec3 spring_force(const Vec3& n, Real kn, Real ks, const Vec3& u) {
  return ks * u + (kn - ks) * n.dot(u) * n;
}
}  // namespace

void AssembledStiffness::apply(const Real* x, Real* y) const {
  // z = M^-1/2 x.
  parallel_for(bodies_, [&](Index i) {
    const auto k = static_cast<std::size_t>(i);
    zt_[k] = inv_sqrt_mass_[k] * Vec3(x[6 * i], x[6 * i + 1], x[6 * i + 2]);
    zr_[k] = inv_sqrt_inertia_[k] * Vec3(x[6 * i + 3], x[6 * i + 4], x[6 * i + 5]);
  });
  std::vector<Vec3>& gf = body_force_;
  std::vector<Vec3>& gt = body_moment_;
  std::fill(gf.begin(), gf.end(), Vec3::Zero());
  std::fill(gt.begin(), gt.end(), Vec3::Zero());
  for (const Network& nw : networks_) {
    const ContactNetwork& net = *nw.net;
    // Each contact's force on b (its points' S u summed) and its moments about both centres.
    parallel_for(net.contact_count(), [&](Index c) {
      const Index a = net.particle_a[c], b = net.particle_b[c];
      const Vec3& n = nw.normal[static_cast<std::size_t>(c)];
      Vec3 f = Vec3::Zero(), ma = Vec3::Zero(), mb = Vec3::Zero();
      for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m) {
        const Vec3 ra = net.point_position0[m] - centre0_[a];
        const Vec3 rb = net.point_position0[m] - centre0_[b];
        const Vec3 u = zt_[b] + zr_[b].cross(rb) - zt_[a] - zr_[a].cross(ra);
        const Vec3 fm = spring_force(n, net.constants[m].kn, net.constants[m].ks, u);
        f += fm;
        ma += ra.cross(fm);
        mb += rb.cross(fm);
      }
      contact_force_[c] = f;
      contact_moment_a_[c] = ma;
      contact_moment_b_[c] = mb;
    });
    // K z on each body: B_b^T S u where it is b, -B_a^T S u where it is a; in a fixed order.
    const BodyContacts& bc = nw.per_body;
    parallel_for(bodies_, [&](Index i) {
      Vec3 f = Vec3::Zero(), t = Vec3::Zero();
      for (Index e = bc.begin[i]; e < bc.mid[i]; ++e) {
        f += contact_force_[bc.entry[e]];
        t += contact_moment_b_[bc.entry[e]];
      }
      for (Index e = bc.mid[i]; e < bc.begin[i + 1]; ++e) {
        f -= contact_force_[bc.entry[e]];
        t -= contact_moment_a_[bc.entry[e]];
      }
      gf[i] += f;
      gt[i] += t;
    });
  }
  for (const Spring& s : springs_) {
    Vec3 u = zt_[s.b] + zr_[s.b].cross(s.arm_b);
    if (s.a >= 0) u -= zt_[s.a] + zr_[s.a].cross(s.arm_a);
    const Vec3 f = spring_force(s.n, s.kn, s.ks, u);
    gf[s.b] += f;
    gt[s.b] += s.arm_b.cross(f);
    if (s.a >= 0) {
      gf[s.a] -= f;
      gt[s.a] -= s.arm_a.cross(f);
    }
  }
  for (const Rotational& r : rotational_) {
    Vec3 turn = zr_[r.b];
    if (r.a >= 0) turn -= zr_[r.a];
    const Vec3 m = r.k * turn;
    gt[r.b] += m;
    if (r.a >= 0) gt[r.a] -= m;
  }
  // y = M^-1/2 K z.
  parallel_for(bodies_, [&](Index i) {
    const auto k = static_cast<std::size_t>(i);
    const Vec3 yt = inv_sqrt_mass_[k] * gf[k];
    const Vec3 yr = inv_sqrt_inertia_[k] * gt[k];
    for (int d = 0; d < 3; ++d) {
      y[6 * i + d] = yt[d];
      y[6 * i + 3 + d] = yr[d];
    }
  });
}

}  // namespace rcdem
