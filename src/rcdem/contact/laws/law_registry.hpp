#pragma once
// The table of contact laws by name: the one place that turns a scenario's choice (contact.law,
// bars.*.interface_softening) into a law. A set of points holds one ContactLaw; the solver picks
// the alternative with std::visit once per loop over its contacts, and the loop over points is a
// template on the law's type, so each point's update is inlined with no dispatch.
//
// Adding a law (docs/architecture.md, "A contact law"): its header, its type in ContactLaw and its
// row in kContactLaws below, the name in the schema's choices, and its tests.
#include <string_view>
#include <type_traits>
#include <variant>

#include "rcdem/config/scenario.hpp"  // ContactParameters
#include "rcdem/contact/laws/bilinear_softening.hpp"
#include "rcdem/contact/laws/elastic.hpp"
#include "rcdem/contact/laws/exponential_softening.hpp"

namespace rcdem {

using ContactLaw = std::variant<BilinearSoftening, Elastic, ExponentialSoftening>;

// The point state every law of the table keeps: a set of points holds one array of records
// (contact/local_point_records.hpp) whatever its law, so the laws share it. A law whose State
// differs stops the build here; it would need ContactState to hold one record array per state,
// chosen with the law (docs/architecture.md, known weak points).
template <class Variant, typename V>
struct CommonPointState;
template <class First, class... Rest, typename V>
struct CommonPointState<std::variant<First, Rest...>, V> {
  using type = typename First::template State<V>;
  static_assert((std::is_same_v<type, typename Rest::template State<V>> && ...),
                "every law in ContactLaw keeps the same point State");
};
template <typename V>
using PointHistory = typename CommonPointState<ContactLaw, V>::type;

struct ContactLawRow {
  std::string_view name;  // the value of contact.law or bars.*.interface_softening
  // Softens (has strengths and fracture energies): may be a nonlinear interface's law.
  bool softening;
  ContactLaw (*make)(const ContactParameters& p);
};

inline constexpr ContactLawRow kContactLaws[] = {
    {"BL", true,
     [](const ContactParameters& p) -> ContactLaw {
       return BilinearSoftening{p.sigma_nt, p.tau, p.G_fn, p.G_fs, p.mu_c};
     }},
    {"EL", false, [](const ContactParameters&) -> ContactLaw { return Elastic{}; }},
    {"exponential", true,
     [](const ContactParameters& p) -> ContactLaw {
       return ExponentialSoftening{p.sigma_nt, p.G_fn, p.mu_c};
     }},
};

// The row named `name`, or null.
const ContactLawRow* find_contact_law(std::string_view name);

// The law named `name` with the parameters p (Table 2's, or an interface's). An unknown name is
// an error naming `key` (the scenario validates names against the same table first).
ContactLaw make_contact_law(std::string_view name, const ContactParameters& p,
                            std::string_view key = "contact.law");

// Whether a law's intact points may be evaluated from their contact's sums
// (contact/elastic_condensation.hpp): the law's kCondensable, an opt-in trait. A law opts in only
// if a point with D = 0 below fn_max and c_max holds exactly fn = kn u_n and fs = -ks u_s, as the
// condensed kernel and its catch-up assume.
template <typename Law>
inline constexpr bool kCondensableLaw = Law::kCondensable;
bool condensable(const ContactLaw& law);

// Whether a condensable law's damaged contacts may be held to their sums while their points stay
// inside their envelopes (contact/held_contacts.hpp): the law's kHoldable, an opt-in trait.
template <typename Law>
inline constexpr bool kHoldableLaw = false;
template <typename Law>
  requires(Law::kHoldable)
inline constexpr bool kHoldableLaw<Law> = true;

}  // namespace rcdem
