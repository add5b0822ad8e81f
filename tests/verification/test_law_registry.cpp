// The table of contact laws (contact/laws/law_registry.hpp): names resolve to their laws with the
// scenario's parameters, the schema offers exactly the table's names, and the traits a loop reads
// (condensable) say what each law allows.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "rcdem/config/schema.hpp"
#include "rcdem/contact/laws/law_registry.hpp"
#include "rcdem/core/error.hpp"

using namespace rcdem;

TEST(LawRegistry, NamesAreUniqueAndEachRowMakesItsOwnLaw) {
  std::set<std::string_view> names;
  const ContactParameters p;
  for (const ContactLawRow& row : kContactLaws) {
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
    const ContactLaw law = make_contact_law(row.name, p);
    EXPECT_EQ(find_contact_law(row.name), &row);
    // Each name makes a different alternative: the table has no row twice under two names.
    EXPECT_EQ(law.index(), static_cast<std::size_t>(&row - kContactLaws)) << row.name;
  }
  EXPECT_EQ(names.size(), std::variant_size_v<ContactLaw>);
}

TEST(LawRegistry, BilinearSofteningTakesTheScenariosParameters) {
  ContactParameters p;
  p.sigma_nt = 3.5e6;
  p.tau = 17e6;
  p.G_fn = 8.0;
  p.G_fs = 2000.0;
  p.mu_c = 0.4;
  const ContactLaw law = make_contact_law("BL", p);
  const auto* bl = std::get_if<BilinearSoftening>(&law);
  ASSERT_NE(bl, nullptr);
  EXPECT_EQ(bl->sigma_nt, p.sigma_nt);
  EXPECT_EQ(bl->tau, p.tau);
  EXPECT_EQ(bl->G_fn, p.G_fn);
  EXPECT_EQ(bl->G_fs, p.G_fs);
  EXPECT_EQ(bl->mu_c, p.mu_c);
  EXPECT_TRUE(std::holds_alternative<Elastic>(make_contact_law("EL", p)));
}

TEST(LawRegistry, AnUnknownNameIsAnErrorNamingTheKeyAndTheChoices) {
  try {
    make_contact_law("CPM", ContactParameters{}, "bars.*.interface_softening");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bars.*.interface_softening"), std::string::npos) << what;
    EXPECT_NE(what.find("\"CPM\""), std::string::npos) << what;
    EXPECT_NE(what.find("\"BL\""), std::string::npos) << what;
  }
}

TEST(LawRegistry, CondensationIsTheLawsOptIn) {
  EXPECT_TRUE(condensable(make_contact_law("BL", ContactParameters{})));
  EXPECT_FALSE(condensable(make_contact_law("EL", ContactParameters{})));
}

// The schema validates a scenario's law names before the table sees them: its choices are the
// table's names (contact.law), and its softening rows (an interface's law).
TEST(LawRegistry, TheSchemaOffersExactlyTheTablesNames) {
  std::vector<std::string> all, softening;
  for (const ContactLawRow& row : kContactLaws) {
    all.emplace_back(row.name);
    if (row.softening) softening.emplace_back(row.name);
  }
  const auto choices = [](const char* key) {
    const config::KeyDecl* decl = config::scenario_schema().find_key(key);
    EXPECT_NE(decl, nullptr) << key;
    return decl ? decl->choices : std::vector<std::string>{};
  };
  EXPECT_EQ(choices("contact.law"), all);
  EXPECT_EQ(choices("bars.*.interface_softening"), softening);
}

// Every law reports the energy its points hold as the SPEC 11 ledger reads it: for the elastic
// branch of each, fn^2/2kn + |fs|^2/2ks.
TEST(LawRegistry, EveryLawsElasticEnergyIsTheSpringsOnItsElasticBranch) {
  LocalPointConstants c;
  c.kn = 1e8;
  c.ks = 3e7;
  c.fn_max = 80.0;
  c.c_max = 400.0;
  for (const ContactLawRow& row : kContactLaws) {
    ContactParameters p;
    p.sigma_nt = 4e6;
    const ContactLaw law = make_contact_law(row.name, p);
    std::visit(
        [&](const auto& l) {
          LocalPointState s;
          l.update(c, s, 0.5 * c.fn_max / c.kn, Vec3(1e-7, -2e-7, 0.0));
          const Real expected = s.fn * s.fn / (2 * c.kn) + s.fs.squaredNorm() / (2 * c.ks);
          EXPECT_EQ(s.damage, 0.0) << row.name;
          EXPECT_NEAR(l.elastic_energy(c, s), expected, 1e-15 * expected) << row.name;
        },
        law);
  }
}
