#pragma once
// The loops over contacts, compiled once per law, each law's in its own translation unit
// (contact/laws/<law>_loops.cpp). GCC stops inlining in a unit once it has grown by
// --param inline-unit-growth (40% over its size): with every law's loop instantiated inside
// simulation.cpp, the point loop's small Eigen operations (differences, dot products, squared
// norms) became calls, each spilling every live vector register, and the cracked AN4 beam's
// step lost 4% (bench/RESULTS.md, "Architecture (issue 29)"). A unit holding one law's loops
// stays within the budget, however many laws the registry holds.
//
// Adding a law (docs/architecture.md, "A contact law"): a line RCDEM_LAW_LOOPS(extern, Law)
// below, and contact/laws/<law>_loops.cpp with RCDEM_LAW_LOOPS(, Law).
#include <variant>

#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/laws/law_registry.hpp"

namespace rcdem {

// Contacts [begin, end) of a network one by one, with no condensation: a steel-concrete
// interface's share of the small tasks.
template <typename Law>
void evaluate_contact_range(const Law& law, const ContactInputs& in, ContactState& cs, Index begin,
                            Index end) {
  for (Index c = begin; c < end; ++c) evaluate_contact(law, in, cs, nullptr, c);
}

// The explicit instantiations of one law's loops (PREFIX empty) or their declarations (PREFIX
// extern, which keeps every other unit from instantiating them again).
#define RCDEM_LAW_LOOPS(PREFIX, Law)                                                            \
  PREFIX template void evaluate_contacts<Law>(const Law&, const ContactInputs&, ContactState&,  \
                                              ElasticCondensation*, const ContactInputs*);      \
  PREFIX template void catch_up_condensed<Law>(const Law&, const ContactInputs&, ContactState&, \
                                               ElasticCondensation&);                           \
  PREFIX template void evaluate_contact_range<Law>(const Law&, const ContactInputs&,            \
                                                   ContactState&, Index, Index)

RCDEM_LAW_LOOPS(extern, BilinearSoftening);
RCDEM_LAW_LOOPS(extern, Elastic);
RCDEM_LAW_LOOPS(extern, ExponentialSoftening);

// A law added to the table without its lines above would still build, its loops instantiated
// inside simulation.cpp again, and silently slow the step: the count stops the build instead.
static_assert(std::variant_size_v<ContactLaw> == 3,
              "each law of ContactLaw needs RCDEM_LAW_LOOPS(extern, Law) here and "
              "contact/laws/<law>_loops.cpp (docs/architecture.md, \"A contact law\")");

}  // namespace rcdem
