#include "rcdem/contact/laws/law_registry.hpp"

#include <string>

#include "rcdem/core/error.hpp"

namespace rcdem {

const ContactLawRow* find_contact_law(std::string_view name) {
  for (const ContactLawRow& row : kContactLaws)
    if (row.name == name) return &row;
  return nullptr;
}

ContactLaw make_contact_law(std::string_view name, const ContactParameters& p,
                            std::string_view key) {
  const ContactLawRow* row = find_contact_law(name);
  if (!row) {
    std::string known;
    for (const ContactLawRow& r : kContactLaws)
      known += (known.empty() ? "\"" : ", \"") + std::string(r.name) + "\"";
    fail("key '{}': unknown contact law \"{}\"; expected one of {}", key, name, known);
  }
  return row->make(p);
}

bool condensable(const ContactLaw& law) {
  return std::visit([](const auto& l) { return kCondensableLaw<std::decay_t<decltype(l)>>; }, law);
}

}  // namespace rcdem
