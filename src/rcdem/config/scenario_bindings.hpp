#pragma once
// The scenario keys bound to the members they set: config/scenario_schema.cpp declares a key and
// its member at once, so the key's default is the member's initial value in its struct (the
// solver keys solver.preset governs excepted: config/solver_preset.hpp), and the
// loader (scenario.cpp) sets every bound member from the value read, with no conversion written
// per key. Keys that set several members or need the specimen to be checked (specimen.shape and
// size, a plate's face and extent, a bar's ends) are converted by hand there.
#include <functional>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/schema.hpp"

namespace rcdem::config {

template <class Target>
struct BoundKey {
  std::string path;  // the full key ("contact.E_bar"), or the key in its instance ("velocity")
  std::function<void(const Value&, Target&)> set;
};

struct ScenarioBindings {
  std::vector<BoundKey<Scenario>> scenario;    // keys outside the named sections
  std::vector<BoundKey<PlateSettings>> plate;  // plates.*.KEY, by KEY
  std::vector<BoundKey<BarSettings>> bar;      // bars.*.KEY, by KEY
  std::vector<BoundKey<GaugeSettings>> gauge;  // gauges.*.KEY, by KEY
  std::vector<BoundKey<SegmentSettings>> segment;  // {plates,bars}.*.program.*.KEY, by KEY
};

const ScenarioBindings& scenario_bindings();

}  // namespace rcdem::config
