#include "experiments/python/python_simulation.hpp"

#include <pybind11/numpy.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include "core/io/input_error.hpp"
#include "experiments/python/interactive_simulation.hpp"
#include "experiments/python/python_errors.hpp"
#include "experiments/python/python_json.hpp"
#include "experiments/run/divergence_check.hpp"
#include "experiments/run/scene_simulation.hpp"

namespace py = pybind11;

namespace drape {

namespace {

// How often a long call takes the GIL back to look for Ctrl-C (PyErr_CheckSignals).
constexpr auto signal_check_period = std::chrono::milliseconds(50);

Hand hand_of(const std::string& name, const std::string& call) {
  if (name == "left") return Hand::Left;
  if (name == "right") return Hand::Right;
  throw InputError(call, "hand", "'" + shorten(name) + "' is not a hand: \"left\" or \"right\"");
}

// The flag of a run's end: the solver's (Simulation stores "flag: message"), or the loop's own.
std::string flag_of(const RunStatus& status) {
  if (status.status == "diverged") return "diverged";
  if (status.reason.rfind("reached integrator.max_steps", 0) == 0) return "max_steps";
  const auto colon = status.reason.find(':');
  return colon == std::string::npos ? status.status : status.reason.substr(0, colon);
}

// The Python object: the simulation (shared with the views it hands out, which keep its state
// alive after close()) and whether a call is stepping it with the GIL released.
class PythonSimulation {
 public:
  PythonSimulation(const Scene& scene, bool live_hands)
      : m_simulation(std::make_shared<InteractiveSimulation>(scene, live_hands)) {}

  /// The simulation for a call; RuntimeError once closed or while another thread steps it.
  InteractiveSimulation& use() {
    if (!m_simulation) throw std::runtime_error("the simulation is closed");
    if (m_busy) throw std::runtime_error("the simulation is stepping in another thread");
    return *m_simulation;
  }
  /// The simulation for a read of its time or a view of its state, allowed while it steps.
  const InteractiveSimulation& read() const {
    if (!m_simulation) throw std::runtime_error("the simulation is closed");
    return *m_simulation;
  }
  void close() {
    use();
    m_simulation.reset();
  }
  bool closed() const { return !m_simulation; }

  /// Runs `advance(simulation, keep_going)` as interruptible() does; raises IntegratorFailure
  /// when the run has failed or diverged, now or before.
  template <class Advance>
  bool stepping(Advance advance) {
    raise_if_failed(use());
    const bool running = interruptible(advance);
    raise_if_failed(use());
    return running;
  }
  /// Runs `call(simulation, keep_going)` without the GIL, keep_going taking it back every
  /// signal_check_period to look for Ctrl-C (KeyboardInterrupt once the call has returned:
  /// it stops between two steps, the state whole).
  template <class Call>
  auto interruptible(Call call) {
    bool interrupted = false;
    auto next_check = std::chrono::steady_clock::now() + signal_check_period;
    const std::function<bool()> keep_going = [&] {
      if (std::chrono::steady_clock::now() < next_check) return true;
      py::gil_scoped_acquire gil;
      interrupted = PyErr_CheckSignals() != 0;
      next_check = std::chrono::steady_clock::now() + signal_check_period;
      return !interrupted;
    };
    auto result = without_gil([&](InteractiveSimulation& sim) { return call(sim, keep_going); });
    if (interrupted) throw py::error_already_set();
    return result;
  }
  /// call(simulation) with the GIL released; other threads' calls meanwhile raise (use()).
  template <class Call>
  auto without_gil(Call call) {
    InteractiveSimulation& simulation = use();
    m_busy = true;
    struct Idle {
      bool& busy;
      ~Idle() { busy = false; }  // after the GIL is back: the scope below ends first
    } idle{m_busy};
    py::gil_scoped_release released;
    return call(simulation);
  }

  py::array view(bool velocities) const {
    const Eigen::VectorXd& y = read().simulation().state();
    const Eigen::Index n3 = y.size() / 2;
    // The capsule owns a share of the simulation: the view outlives close() and `self`.
    auto* owner = new std::shared_ptr<InteractiveSimulation>(m_simulation);
    const py::capsule base(owner, [](void* p) {
      delete static_cast<std::shared_ptr<InteractiveSimulation>*>(p);
    });
    py::array_t<double> array({static_cast<py::ssize_t>(n3 / 3), py::ssize_t{3}},
                              {3 * static_cast<py::ssize_t>(sizeof(double)),
                               static_cast<py::ssize_t>(sizeof(double))},
                              y.data() + (velocities ? n3 : 0), base);
    array.attr("setflags")(py::arg("write") = false);
    return array;
  }

  void set_view(bool velocities, py::handle values) {
    InteractiveSimulation& simulation = use();
    const char* field = velocities ? "velocities" : "positions";
    const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
    if (!array) {
      PyErr_Clear();
      throw InputError("Simulation", field, "expected an (N, 3) array of numbers");
    }
    const Eigen::Index n3 = simulation.simulation().state().size() / 2;
    if (array.ndim() != 2 || array.shape(1) != 3 || array.shape(0) * 3 != n3) {
      std::string shape;
      for (py::ssize_t k = 0; k < array.ndim(); ++k) shape += (k ? ", " : "") + std::to_string(array.shape(k));
      throw InputError("Simulation", field,
                       "expected shape (" + std::to_string(n3 / 3) + ", 3), got (" + shape + ")");
    }
    simulation.set_block(velocities, Eigen::Map<const Eigen::VectorXd>(array.data(), n3));
  }

 private:
  static void raise_if_failed(const InteractiveSimulation& simulation) {
    const RunStatus& status = simulation.simulation().status();
    if (status.status == "failed" || status.status == "diverged")
      throw RunEndedError(status.status, flag_of(status), simulation.simulation().time(),
                          status.reason);
  }

  std::shared_ptr<InteractiveSimulation> m_simulation;
  bool m_busy = false;  ///< read and written with the GIL held
};

double checked_time(double t) {
  if (std::isnan(t)) throw InputError("Simulation.advance", "t", "not a number");
  return t;
}

std::optional<Vec3> hand_position(py::handle xyz) {
  if (xyz.is_none()) return std::nullopt;
  const auto array = py::array_t<double, py::array::forcecast>::ensure(xyz);
  if (!array || array.ndim() != 1 || array.shape(0) != 3) {
    PyErr_Clear();
    throw InputError("Simulation.set_hand", "xyz", "expected 3 numbers (x, y, z) or None");
  }
  return Vec3(array.at(0), array.at(1), array.at(2));
}

}  // namespace

void bind_simulation(py::module_& module) {
  using Self = PythonSimulation;
  py::class_<Self>(module, "Simulation",
                   "A scene stepped from Python, as drapelab run steps it (docs/python.md).")
      .def(py::init<const Scene&, bool>(), py::arg("scene"), py::kw_only(),
           py::arg("live_hands") = false)
      .def("step", [](Self& s) {
             return s.stepping([](InteractiveSimulation& sim, const auto& go) { return sim.step(go); });
           },
           "One step; False once the run has ended.")
      .def("advance",
           [](Self& s, double t) {
             checked_time(t);
             return s.stepping(
                 [t](InteractiveSimulation& sim, const auto& go) { return sim.advance(t, go); });
           },
           py::arg("t"), "Steps to time t [s] (at most the duration), events applied on the way.")
      .def_property_readonly("time", [](const Self& s) { return s.read().simulation().time(); })
      .def_property_readonly("duration", [](Self& s) { return s.use().run().scene().duration; })
      .def_property_readonly("status", [](Self& s) { return s.use().simulation().status().status; })
      .def_property("positions", [](const Self& s) { return s.view(false); },
                    [](Self& s, py::handle v) { s.set_view(false, v); },
                    "(N, 3) read-only view of the positions [m]; assigning copies and projects.")
      .def_property("velocities", [](const Self& s) { return s.view(true); },
                    [](Self& s, py::handle v) { s.set_view(true, v); },
                    "(N, 3) read-only view of the velocities [m/s]; assigning copies and projects.")
      .def_property_readonly("fixed",
                             [](Self& s) {
                               const auto& mask = s.use().run().system().constraints().mask();
                               py::array_t<bool> out(static_cast<py::ssize_t>(mask.size()));
                               for (std::size_t i = 0; i < mask.size(); ++i) out.mutable_at(i) = mask[i] != 0;
                               return out;
                             })
      .def("energy",
           [](Self& s) {
             const InteractiveSimulation& sim = s.use();
             const EnergyBreakdown e = energy_of(sim.run().system(), sim.simulation().state());
             py::dict out;
             out["kinetic"] = e.kinetic;
             out["spring"] = e.spring;
             out["gravity"] = e.gravity;
             out["collision"] = e.collision;
             out["total"] = e.total();
             return out;
           },
           "The energy of the state [J] by term (docs/model.md).")
      .def_property_readonly("counters",
                             [](Self& s) { return python_of(s.use().simulation().integrator().counters().to_json()); })
      .def_property_readonly("events",
                             [](Self& s) {
                               const InteractiveSimulation& sim = s.use();
                               nlohmann::json events = nlohmann::json::array();
                               for (const ManipulationEvent& e : sim.simulation().manipulator().events())
                                 events.push_back(e.to_json(sim.run().system().cloth()));
                               return python_of(events);
                             })
      .def("press", [](Self& s, const std::string& key) { s.use().press(key); }, py::arg("key"))
      .def("set_hand",
           [](Self& s, const std::string& hand, py::handle xyz) {
             s.use().set_hand(hand_of(hand, "Simulation.set_hand"), hand_position(xyz));
           },
           py::arg("hand"), py::arg("xyz"))
      .def("hold_candidate",
           [](Self& s, const std::string& hand) -> py::object {
             const int i = s.use().hold_candidate(hand_of(hand, "Simulation.hold_candidate"));
             return i < 0 ? py::object(py::none()) : py::object(py::int_(i));
           },
           py::arg("hand"))
      .def("run",
           [](Self& s, py::handle out_dir, bool overwrite) {
             const std::string dir = py::str(py::module_::import("os").attr("fspath")(out_dir));
             const RunOutcome outcome =
                 s.interruptible([&](InteractiveSimulation& sim, const auto& keep_going) {
                   return sim.run_to_folder(dir, overwrite, keep_going);
                 });
             return python_of(outcome.summary);
           },
           py::arg("out_dir"), py::kw_only(), py::arg("overwrite") = false,
           "Runs the scene into out_dir as drapelab run does; returns summary.json's contents. "
           "Ctrl-C stops it between two steps (KeyboardInterrupt) and leaves the folder "
           "without summary.json.")
      .def("write_recording",
           [](Self& s, py::handle file) {
             const std::string path = py::str(py::module_::import("os").attr("fspath")(file));
             return python_of(s.use().write_recording(path));
           },
           py::arg("file"))
      .def("close", &Self::close)
      .def_property_readonly("closed", &Self::closed)
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](Self& s, py::args) {
        if (!s.closed()) s.close();
      });
}

}  // namespace drape
