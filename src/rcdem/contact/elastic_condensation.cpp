#include "rcdem/contact/elastic_condensation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rcdem {

ElasticCondensation ElasticCondensation::build(const ContactNetwork& net,
                                               const std::vector<Vec3>& x0) {
  ElasticCondensation e;
  const auto nc = static_cast<std::size_t>(net.contact_count());
  e.sums.resize(nc);
  e.eligible.assign(nc, 0);
  for (Index c = 0; c < net.contact_count(); ++c) {
    CondensedContact& k = e.sums[static_cast<std::size_t>(c)];
    const Index begin = net.point_begin[c], end = net.point_begin[c + 1];
    if (end == begin) continue;
    const Vec3& xa0 = x0[net.particle_a[c]];
    const Real alpha = net.constants[begin].ks / net.constants[begin].kn;
    bool uniform = true;
    Vec3 moment = Vec3::Zero();
    k.u_n0 = k.u_s0 = std::numeric_limits<Real>::infinity();
    for (Index m = begin; m < end; ++m) {
      const LocalPointConstants& p = net.constants[m];
      uniform &= std::abs(p.ks - alpha * p.kn) <= 1e-12 * p.ks;
      k.k_n += p.kn;
      moment += p.kn * (net.point_position0[m] - xa0);
      k.u_n0 = std::min(k.u_n0, p.fn_max / p.kn);
      k.u_s0 = std::min(k.u_s0, p.c_max / p.ks);
    }
    k.alpha = alpha;
    k.centroid = moment / k.k_n;
    Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
    for (Index m = begin; m < end; ++m) {
      const Vec3 rho = net.point_position0[m] - xa0 - k.centroid;
      j += net.constants[m].kn * rho * rho.transpose();
      k.radius = std::max(k.radius, rho.norm());
    }
    k.j[0] = j(0, 0);
    k.j[1] = j(1, 1);
    k.j[2] = j(2, 2);
    k.j[3] = j(0, 1);
    k.j[4] = j(0, 2);
    k.j[5] = j(1, 2);
    // A zero or NaN limit (zero strength) never passes the bound; nothing else to exclude.
    e.eligible[static_cast<std::size_t>(c)] = uniform && k.k_n > 0 && std::isfinite(alpha);
  }
  e.intact = e.eligible;
  e.condensed.assign(nc, 0);
  return e;
}

void ElasticCondensation::reset_flags(const ContactNetwork& net, const std::vector<Real>& damage) {
  for (Index c = 0; c < net.contact_count(); ++c) {
    bool all_intact = eligible[static_cast<std::size_t>(c)] != 0;
    for (Index m = net.point_begin[c]; m < net.point_begin[c + 1]; ++m)
      all_intact &= damage[static_cast<std::size_t>(m)] == 0;
    intact[static_cast<std::size_t>(c)] = all_intact;
  }
  std::fill(condensed.begin(), condensed.end(), std::uint8_t{0});
  any_condensed = false;
}

Index ElasticCondensation::condensed_count() const {
  return static_cast<Index>(std::count(condensed.begin(), condensed.end(), std::uint8_t{1}));
}

Index ElasticCondensation::condensed_point_count(const ContactNetwork& net) const {
  Index n = 0;
  for (Index c = 0; c < static_cast<Index>(condensed.size()); ++c)
    if (condensed[static_cast<std::size_t>(c)]) n += net.points_of(c);
  return n;
}

}  // namespace rcdem
