#include "rcdem/contact/law_loops.hpp"

#include <type_traits>
#include <variant>

namespace rcdem {

void evaluate_contacts(const ContactLaw& law, const ContactInputs& in, ContactState& cs,
                       ElasticCondensation* cond, const ContactInputs* previous, Real* energy) {
  std::visit(
      [&](const auto& l) {
        if constexpr (kCondensableLaw<std::decay_t<decltype(l)>>)
          evaluate_contacts(l, in, cs, cond, previous, energy);
        else
          evaluate_contacts(l, in, cs, nullptr, nullptr, energy);
      },
      law);
}

void catch_up_condensed(const ContactLaw& law, const ContactInputs& in, ContactState& cs,
                        ElasticCondensation& cond) {
  std::visit(
      [&](const auto& l) {
        if constexpr (kCondensableLaw<std::decay_t<decltype(l)>>)
          catch_up_condensed(l, in, cs, cond);
      },
      law);
}

void evaluate_contact_range(const ContactLaw& law, const ContactInputs& in, ContactState& cs,
                            Index begin, Index end) {
  std::visit(
      [&](const auto& l) {
        for (Index c = begin; c < end; ++c) evaluate_contact(l, in, cs, nullptr, c);
      },
      law);
}

}  // namespace rcdem
