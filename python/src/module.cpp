// `import rcdem` (issue 45, item 1; docs/python.md): the scenario with the CLI's checks, the
// simulation stepped or run from Python, and numpy views of its state without copies. Python
// wrappers and the readers of run directories are in python/rcdem/*.py.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rcdem/config/scenario.hpp"
#include "rcdem/config/scenario_overrides.hpp"
#include "rcdem/core/error.hpp"
#include "rcdem/core/progress.hpp"
#include "rcdem/core/thread_waiting.hpp"
#include "rcdem/run/checkpoint.hpp"
#include "rcdem/run/run.hpp"
#include "rcdem/run/run_manifest.hpp"
#include "rcdem/run/run_output.hpp"
#include "rcdem/solver/simulation.hpp"
#include "rcdem/solver/test_measures.hpp"
#include "rcdem/specimens/specimen.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace rcdem;

namespace {

// A scenario as Python holds it: its text, where it came from (its includes are found from
// there), and the keys set on it, which later errors name as the CLI's --set does.
struct PyScenario {
  Scenario scenario;
  std::vector<config::Override> set;

  static PyScenario load(const fs::path& path) { return {load_scenario(path), {}}; }
  static PyScenario from_text(const std::string& text, const fs::path& source) {
    PyScenario s{parse_scenario(text, source.string()), {}};
    s.scenario.source = source;
    return s;
  }
  // key = value (TOML text), checked as the CLI's --set.
  void set_key(const std::string& key, const std::string& value) {
    const config::Override o{key, value, key + "=" + value};
    config::check_override(o);
    const std::string text = config::with_override(scenario.text, scenario.source.string(), o);
    std::vector<config::Override> all = set;
    all.push_back(o);
    Scenario next = parse_scenario(text, scenario.source.string(), all);
    next.source = scenario.source;
    scenario = std::move(next);
    set = std::move(all);
  }
};

// A numpy array over `count` records of `stride` bytes from `first`, kept alive by `owner`.
template <class T>
py::array view(const T* first, py::ssize_t count, std::vector<py::ssize_t> shape_tail,
               py::ssize_t stride, py::handle owner, bool writable) {
  std::vector<py::ssize_t> shape{count}, strides{stride};
  py::ssize_t inner = static_cast<py::ssize_t>(sizeof(T));
  for (auto it = shape_tail.rbegin(); it != shape_tail.rend(); ++it) {
    strides.insert(strides.begin() + 1, inner);
    inner *= *it;
  }
  shape.insert(shape.end(), shape_tail.begin(), shape_tail.end());
  py::array a(py::dtype::of<T>(), shape, strides, first, owner);
  if (!writable) py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// The simulation with its test's measures (load, displacement, gauges), built from a scenario.
class PySimulation {
 public:
  explicit PySimulation(const PyScenario& s) : scenario_(s.scenario) {
    py::gil_scoped_release release;
    sim_ = std::make_unique<Simulation>(scenario_, build_specimen(scenario_));
    measures_ = std::make_unique<TestMeasures>(*sim_, scenario_);
  }
  Simulation& sim() { return *sim_; }
  const Scenario& scenario() const { return scenario_; }
  const TestMeasures& measures() const { return *measures_; }

  void step(std::int64_t n) {
    if (n < 0) fail("step: n = {} steps: expected 0 or more", n);
    py::gil_scoped_release release;
    for (std::int64_t i = 0; i < n; ++i) sim_->step();
  }

  py::dict run(const fs::path& out, std::int64_t every, const py::object& callback,
               std::int64_t checkpoint_every, bool resume, const py::object& until);
  void write_snapshot(const fs::path& dir, bool binary, bool facets) {
    py::gil_scoped_release release;
    fs::create_directories(dir);
    io::SnapshotWriter(dir, binary, facets).write(*sim_);
  }

 private:
  Scenario scenario_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<TestMeasures> measures_;
};

// What a callback's return value asks of the run: None or True go on, False stops the run,
// rcdem.INTERRUPT (the string "interrupt") interrupts it as a signal would.
RunDecision decision_of(const py::object& r) {
  if (r.is_none()) return RunDecision::Continue;
  if (py::isinstance<py::str>(r)) {
    if (r.cast<std::string>() == "interrupt") return RunDecision::Interrupt;
    fail("run callback returned '{}': expected None, True, False or rcdem.INTERRUPT",
         r.cast<std::string>());
  }
  return r.cast<bool>() ? RunDecision::Continue : RunDecision::Stop;
}

// `until`: None, a step count (int) or a simulation time (float, s) at which the run ends.
struct RunEnd {
  std::int64_t step = -1;
  Real time = -1.0;
  explicit RunEnd(const py::object& until) {
    if (until.is_none()) return;
    if (py::isinstance<py::int_>(until)) {
      step = until.cast<std::int64_t>();
      if (step < 0) fail("run: until = {} steps: expected 0 or more", step);
    } else {
      time = until.cast<Real>();
      if (!(time >= 0.0)) fail("run: until = {} s: expected a time of 0 or more", time);
    }
  }
  bool set() const { return step >= 0 || time >= 0.0; }
  bool reached(const Simulation& s) const {
    return (step >= 0 && s.steps() >= step) || (time >= 0.0 && s.time() >= time);
  }
};

py::dict PySimulation::run(const fs::path& out, std::int64_t every, const py::object& callback,
                           std::int64_t checkpoint_every, bool resume, const py::object& until) {
  if (every < 1) fail("run: every = {}: expected a step count of 1 or more", every);
  const RunEnd end(until);
  fs::create_directories(out);
  RunOptions opt;
  opt.resume = resume;
  opt.checkpoint_every_steps = checkpoint_every;
  opt.command = {"python", "rcdem.Simulation.run"};
  if (!callback.is_none() || end.set()) {
    // Every step when there is an end to check (a C++ test), Python only every `every` steps.
    opt.decide_every = end.set() ? 1 : every;
    opt.decide = [&, end](Simulation& s) {
      if (end.reached(s)) return RunDecision::Until;
      if (callback.is_none() || s.steps() % every != 0) return RunDecision::Continue;
      py::gil_scoped_acquire acquire;
      return decision_of(callback(py::cast(this, py::return_value_policy::reference)));
    };
  }
  RunSummary r;
  {
    py::gil_scoped_release release;
    r = run_simulation(scenario_, *sim_, out, opt);
  }
  if (r.json.is_null()) {  // interrupted: what the run has so far, and where it continues from
    r.json = {{"stop_reason", r.stop_reason},
              {"steps", r.steps},
              {"time_s", r.time},
              {"peak_load_N", r.peak_load},
              {"checkpoint", r.checkpoint.string()}};
  }
  return py::module_::import("json").attr("loads")(r.json.dump());
}

py::dict energies(const Simulation& sim) {
  const Energy e = sim.energy();
  py::dict d;
  d["external_work"] = e.external_work;
  d["strain"] = e.strain;
  d["kinetic"] = e.kinetic;
  d["damage"] = e.damage;
  d["friction"] = e.friction;
  d["damping"] = e.damping;
  d["plastic"] = e.plastic;
  d["balance_error"] = e.balance_error();
  return d;
}

void bind_scenario(py::module_& m) {
  py::class_<PyScenario>(m, "_Scenario")
      .def_static("load", &PyScenario::load, py::arg("path"))
      .def_static("from_text", &PyScenario::from_text, py::arg("text"), py::arg("source"))
      .def("set_toml", &PyScenario::set_key, py::arg("key"), py::arg("value"))
      .def("to_toml", [](const PyScenario& s) { return s.scenario.text; })
      .def_property_readonly("source", [](const PyScenario& s) { return s.scenario.source; })
      .def_property_readonly("set_keys", [](const PyScenario& s) {
        std::vector<std::string> out;
        for (const auto& o : s.set) out.push_back(o.given);
        return out;
      });
}

void bind_state(py::class_<PySimulation>& c) {
  const auto bodies = [](bool writable, auto member, std::vector<py::ssize_t> tail) {
    return [=](py::object self) {
      Bodies& b = self.cast<PySimulation&>().sim().bodies();
      auto& v = b.*member;
      using Item = typename std::remove_reference_t<decltype(v)>::value_type;
      return view(reinterpret_cast<const Real*>(v.data()), static_cast<py::ssize_t>(v.size()),
                  tail, static_cast<py::ssize_t>(sizeof(Item)), self, writable);
    };
  };
  c.def_property_readonly("position", bodies(false, &Bodies::position, {3}))
      .def_property_readonly("position0", bodies(false, &Bodies::position0, {3}))
      .def_property_readonly("velocity", bodies(true, &Bodies::velocity, {3}))
      .def_property_readonly("angular_velocity", bodies(false, &Bodies::angular_velocity, {3}))
      .def_property_readonly("orientation", bodies(false, &Bodies::orientation, {4}))
      .def_property_readonly("force", bodies(false, &Bodies::force, {3}))
      .def_property_readonly("torque", bodies(false, &Bodies::torque, {3}))
      .def_property_readonly("mass", bodies(false, &Bodies::mass, {}))
      .def_property_readonly("radius", bodies(false, &Bodies::radius, {}));
  // A field of every concrete local point, read in place in the point records (the condensed
  // contacts' points brought up to date first, as every output does).
  const auto points = [](Real PointHistory<PlaneVec>::*field) {
    return [=](py::object self) {
      const ContactState& cs = self.cast<PySimulation&>().sim().contacts();
      return view(&(cs.point.data()->history.*field), static_cast<py::ssize_t>(cs.point.size()),
                  {}, static_cast<py::ssize_t>(sizeof(LocalPointRecord)), self, false);
    };
  };
  c.def_property_readonly("point_damage", points(&PointHistory<PlaneVec>::damage))
      .def_property_readonly("point_opening", points(&PointHistory<PlaneVec>::un));
  c.def_property_readonly("contact_particles", [](py::object self) {
    const ContactNetwork& net = self.cast<PySimulation&>().sim().specimen().contacts;
    py::array_t<Index> out({static_cast<py::ssize_t>(net.contact_count()), py::ssize_t{2}});
    auto w = out.mutable_unchecked<2>();
    for (Index k = 0; k < net.contact_count(); ++k) {
      w(k, 0) = net.particle_a[k];
      w(k, 1) = net.particle_b[k];
    }
    return out;
  });
  c.def_property_readonly("contact_point_begin", [](py::object self) {
    const ContactNetwork& net = self.cast<PySimulation&>().sim().specimen().contacts;
    return view(net.point_begin.data(), static_cast<py::ssize_t>(net.point_begin.size()), {},
                static_cast<py::ssize_t>(sizeof(Index)), self, false);
  });
  c.def_property_readonly("contact_force", [](py::object self) {
    const ContactState& cs = self.cast<PySimulation&>().sim().contacts();
    return view(reinterpret_cast<const Real*>(cs.force_b.data()),
                static_cast<py::ssize_t>(cs.force_b.size()), {3},
                static_cast<py::ssize_t>(sizeof(Vec3)), self, false);
  });
  c.def_property_readonly("node_axial_force", [](py::object self) {
    const auto& s = self.cast<PySimulation&>().sim().node_states();
    return view(s.empty() ? nullptr : &s[0].axial_force, static_cast<py::ssize_t>(s.size()), {},
                static_cast<py::ssize_t>(sizeof(NodeState)), self, false);
  });
}

// The item called `name` (a plate, a pulled bar), or an rcdem.Error "WHAT 'NAME'".
template <class T>
T& named(std::vector<T>& items, const std::string& name, const char* what) {
  for (T& item : items)
    if (item.name == name) return item;
  fail("{} '{}'", what, name);
}

void bind_measures(py::class_<PySimulation>& c) {
  c.def_property_readonly("load", [](const PySimulation& s) { return s.measures().load(); })
      .def_property_readonly("displacement",
                             [](const PySimulation& s) { return s.measures().displacement(); })
      .def_property_readonly("gauges",
                             [](PySimulation& s) {
                               py::dict d;
                               for (const Gauge& g : s.measures().gauges())
                                 d[py::str(g.name())] = g.value(s.sim());
                               return d;
                             })
      .def_property_readonly("energies", [](PySimulation& s) { return energies(s.sim()); })
      .def_property_readonly("plates", [](PySimulation& s) {
        py::dict d;
        for (const Plate& p : s.sim().plates()) {
          py::dict q;
          q["displacement"] = p.displacement;
          q["force"] = std::vector<Real>{p.force.x(), p.force.y(), p.force.z()};
          q["load"] = p.load();
          q["work"] = p.work;
          q["velocity"] = p.velocity;
          d[py::str(p.name)] = q;
        }
        return d;
      });
  c.def(
      "set_plate_velocity",
      [](PySimulation& s, const std::string& name, Real v) {
        named(s.sim().plates(), name, "set_plate_velocity: no plate").set_velocity(v);
      },
      py::arg("name"), py::arg("velocity"));
  c.def(
      "set_pull_velocity",
      [](PySimulation& s, const std::string& name, Real v) {
        named(s.sim().pulled_bars(), name, "set_pull_velocity: no pulled bar").set_speed(v);
      },
      py::arg("name"), py::arg("velocity"));
  c.def_property_readonly("pulled_bars", [](PySimulation& s) {
    py::dict d;
    for (const PulledBar& b : s.sim().pulled_bars()) {
      py::dict q;
      q["displacement"] = b.displacement;
      q["load"] = b.load();
      q["work"] = b.work;
      q["velocity"] = b.speed;
      d[py::str(b.name)] = q;
    }
    return d;
  });
}

void bind_simulation(py::module_& m) {
  py::class_<PySimulation> c(m, "_Simulation");
  c.def(py::init<const PyScenario&>(), py::arg("scenario"))
      .def("step", &PySimulation::step, py::arg("n") = 1)
      .def("run", &PySimulation::run, py::arg("out"), py::arg("every") = 1,
           py::arg("callback") = py::none(), py::arg("checkpoint_every") = 0,
           py::arg("resume") = false, py::arg("until") = py::none())
      .def("write_snapshot", &PySimulation::write_snapshot, py::arg("directory"),
           py::arg("binary") = true, py::arg("facets") = true)
      .def_property_readonly("time", [](PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("steps", [](PySimulation& s) { return s.sim().steps(); })
      .def_property_readonly("time_step", [](PySimulation& s) { return s.sim().time_step(); })
      .def_property_readonly("concrete_count",
                             [](PySimulation& s) { return s.sim().concrete_count(); })
      .def_property_readonly("body_count", [](PySimulation& s) { return s.sim().bodies().size(); })
      .def_property_readonly("damaged_points",
                             [](PySimulation& s) { return s.sim().damaged_points(); })
      .def_property_readonly("broken_points",
                             [](PySimulation& s) { return s.sim().broken_points(); })
      .def(
          "save_checkpoint",
          [](PySimulation& s, const fs::path& dir) {
            fs::create_directories(dir);
            s.sim().catch_up_condensed_points();
            return io::write_checkpoint(dir, io::CheckpointParts{&s.sim()},
                                        io::fnv1a64(s.scenario().text));
          },
          py::arg("directory"))
      .def(
          "restore_checkpoint",
          [](PySimulation& s, const fs::path& file) {
            io::restore_checkpoint(file, io::CheckpointParts{&s.sim()},
                                   io::fnv1a64(s.scenario().text));
          },
          py::arg("file"));
  bind_state(c);
  bind_measures(c);
}

}  // namespace

PYBIND11_MODULE(_rcdem, m) {
  m.doc() = "rcdem's simulator (docs/python.md); use the rcdem package, not this module";
  prefer_passive_thread_waiting();  // as the CLI does (core/thread_waiting.hpp)
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error(e.what());
    }
  });
  m.def("set_quiet", &Progress::set_quiet_default, py::arg("quiet"));
  m.def("run_directory_scenario", [](const fs::path& dir) {
    return PyScenario{run_directory_scenario(dir), {}};
  });
  bind_scenario(m);
  bind_simulation(m);
}
