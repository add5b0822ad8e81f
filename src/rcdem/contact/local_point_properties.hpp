#pragma once
// Stiffness and strength of one local contact point from its area, paper (3)-(6).
#include "rcdem/config/scenario.hpp"
#include "rcdem/contact/laws/local_point_state.hpp"
#include "rcdem/core/types.hpp"

namespace rcdem {

// (3) k_n = E_bar A_c / d, (4) k_s = alpha k_n, (5) F_n,max = sigma_n,t A_c, (6) C_max = tau A_c.
inline LocalPointConstants local_point_properties(const ContactParameters& p, Real area,
                                                  Real distance) {
  LocalPointConstants q;
  q.kn = p.E_bar * area / distance;
  q.ks = p.alpha * q.kn;
  q.fn_max = p.sigma_nt * area;
  q.c_max = p.tau * area;
  return q;
}

}  // namespace rcdem
