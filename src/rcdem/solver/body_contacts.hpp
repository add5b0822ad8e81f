#pragma once
// For each body, the contacts it takes part in (CSR), so that forces are gathered per body in a
// fixed order: no atomics, and the same sum whatever the thread count (DESIGN principle 3).
#include <vector>

#include "rcdem/core/types.hpp"
#include "rcdem/state/contact_network.hpp"

namespace rcdem {

struct BodyContacts {
  std::vector<Index> begin;  // size bodies + 1
  std::vector<Index> entry;  // contact index * 2 + (1 if the body is B, 0 if A)

  static BodyContacts build(const ContactNetwork& net, Index bodies) {
    BodyContacts bc;
    bc.begin.assign(static_cast<std::size_t>(bodies) + 1, 0);
    for (Index c = 0; c < net.contact_count(); ++c) {
      ++bc.begin[net.particle_a[c] + 1];
      ++bc.begin[net.particle_b[c] + 1];
    }
    for (Index i = 0; i < bodies; ++i) bc.begin[i + 1] += bc.begin[i];
    bc.entry.resize(static_cast<std::size_t>(bc.begin.back()));
    std::vector<Index> fill(bc.begin.begin(), bc.begin.end() - 1);
    for (Index c = 0; c < net.contact_count(); ++c) {
      bc.entry[fill[net.particle_a[c]]++] = 2 * c;
      bc.entry[fill[net.particle_b[c]]++] = 2 * c + 1;
    }
    return bc;
  }
};

}  // namespace rcdem
