#pragma once
// The loops over a set of contacts for the law it holds: the law picked once per loop
// (std::visit), every law of ContactLaw instantiated in law_loops.cpp, so that a new law needs
// nothing here or in the solver. That unit is compiled with a larger inlining budget
// (CMakeLists.txt says why; regression.hot_loop_inlined checks the optimised binary).
#include "rcdem/contact/contact_loop.hpp"
#include "rcdem/contact/laws/law_registry.hpp"

namespace rcdem {

// evaluate_contacts (contact_loop.hpp) with the law `law` holds; `cond` and `previous` are used
// only by a condensable law (kCondensableLaw), the others go through their points; `energy`, per
// contact, receives each one's elastic energy when given.
void evaluate_contacts(const ContactLaw& law, const ContactInputs& in, ContactState& cs,
                       ElasticCondensation* cond = nullptr,
                       const ContactInputs* previous = nullptr, Real* energy = nullptr);

// catch_up_condensed (contact_loop.hpp) with the law `law` holds; nothing for a law that is not
// condensable (its contacts are never condensed).
void catch_up_condensed(const ContactLaw& law, const ContactInputs& in, ContactState& cs,
                        ElasticCondensation& cond);

// Contacts [begin, end) of a network one by one, with no condensation (a steel-concrete
// interface's share of the small tasks).
void evaluate_contact_range(const ContactLaw& law, const ContactInputs& in, ContactState& cs,
                            Index begin, Index end);

}  // namespace rcdem
