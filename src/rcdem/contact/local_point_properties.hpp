#pragma once
// Stiffness and strength of one local contact point from its area, paper (3)-(6).
#include "rcdem/core/types.hpp"
#include "rcdem/io/scenario.hpp"

namespace rcdem {

struct LocalPointProperties {
  Real kn = 0.0;      // (3) k_n = E_bar A_c / d            [N/m]
  Real ks = 0.0;      // (4) k_s = alpha k_n                 [N/m]
  Real fn_max = 0.0;  // (5) F_n,max = sigma_n,t A_c         [N]
  Real c_max = 0.0;   // (6) C_max = tau A_c                 [N]
};

inline LocalPointProperties local_point_properties(const ContactParameters& p, Real area,
                                                   Real distance) {
  LocalPointProperties q;
  q.kn = p.E_bar * area / distance;
  q.ks = p.alpha * q.kn;
  q.fn_max = p.sigma_nt * area;
  q.c_max = p.tau * area;
  return q;
}

}  // namespace rcdem
