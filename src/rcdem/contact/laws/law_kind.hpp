#pragma once
// Which contact law a set of points uses, and the one place that turns that runtime choice into
// a concrete type: the solver's loop over points is a template on the law, picked once per loop
// here, so the per-point call is inlined with no virtual dispatch.
#include <utility>

#include "rcdem/contact/laws/bilinear_softening.hpp"
#include "rcdem/contact/laws/elastic.hpp"

namespace rcdem {

enum class LawKind { BilinearSoftening, Elastic };

// Calls f(law) with the law named by `kind`. f must return the same type for both laws.
template <typename F>
decltype(auto) with_law(LawKind kind, const BilinearSoftening& bilinear, const Elastic& elastic,
                        F&& f) {
  if (kind == LawKind::Elastic) return std::forward<F>(f)(elastic);
  return std::forward<F>(f)(bilinear);
}

}  // namespace rcdem
