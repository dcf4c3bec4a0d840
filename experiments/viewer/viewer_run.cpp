#include "experiments/viewer/viewer_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/io/input_error.hpp"
#include "core/io/json_reader.hpp"
#include "experiments/output/run_folder.hpp"
#include "experiments/viewer/csv_table.hpp"

namespace drape {

namespace fs = std::filesystem;

namespace {

// A count or an index read from the scene: an integer within [low, high].
int scene_integer(const nlohmann::json& value, const std::string& file, const std::string& field,
                  int low, int high) {
  if (!value.is_number_integer() || value.get<long long>() < low || value.get<long long>() > high)
    throw InputError(file, field,
                     "expected an integer in [" + std::to_string(low) + ", " +
                         std::to_string(high) + "], got " + value.dump());
  return value.get<int>();
}

// A run writes its rows in increasing time (docs/outputs.md): a time at or before the one of the
// row before was played out of order, or twice, on the page's slider.
void check_time_increases(const CsvTable& table, int r, double t, double before) {
  if (!(t > before))
    throw InputError(table.file(), table.line(r),
                     fmt::format("column 't': t = {} is not after the time before it, t = {} (times "
                                 "must increase)", t, before));
}

// A coordinate of the dress form or a hand, for the page's single precision: a finite double
// beyond float's range (1e300) would be inf there, as a trace frame's (read_viewer_run).
float coordinate(const CsvTable& table, int r, int c) {
  const double value = table.finite(r, c);
  if (std::abs(value) > std::numeric_limits<float>::max())
    throw InputError(table.file(), table.line(r),
                     fmt::format("a coordinate of {} is not finite in single precision", value));
  return static_cast<float>(value);
}

// Frames of trace.csv: rows grouped by time, every particle once a frame, in index order.
std::vector<ViewerFrame> read_trace(const fs::path& file, int particles) {
  const CsvTable table(file, {"t", "index", "x", "y", "z", "fixed", "event"});
  if (table.rows() % particles != 0)
    throw InputError(table.file(), "",
                     std::to_string(table.rows()) + " rows are not whole frames of " +
                         std::to_string(particles) + " particles");
  std::vector<ViewerFrame> frames(table.rows() / particles);
  for (size_t f = 0; f < frames.size(); ++f) {
    ViewerFrame& frame = frames[f];
    const int first = static_cast<int>(f) * particles;
    frame.t = table.finite(first, 0);
    if (f > 0) check_time_increases(table, first, frame.t, frames[f - 1].t);
    frame.positions.resize(3 * static_cast<size_t>(particles));
    for (int i = 0; i < particles; ++i) {
      const int r = first + i;
      if (table.at(r, 1) != i || table.at(r, 0) != frame.t)
        throw InputError(table.file(), "line " + std::to_string(r + 2),
                         "expected particle " + std::to_string(i) +
                             " of the frame at t = " + std::to_string(frame.t));
      for (int k = 0; k < 3; ++k)
        frame.positions[3 * i + k] = static_cast<float>(table.at(r, 2 + k));
      if (table.integer(r, 5, 0, 1) != 0) frame.fixed.push_back(i);
      const bool event = table.integer(r, 6, 0, 1) != 0;  // checked in every row
      frame.event = frame.event || event;
    }
  }
  return frames;
}

// The final state as a single frame at the summary's simulated time.
ViewerFrame read_state(const fs::path& file, int particles, double t) {
  const CsvTable table(file, {"index", "x", "y", "z", "fixed"});
  if (table.rows() != particles)
    throw InputError(table.file(), "",
                     std::to_string(table.rows()) + " rows, expected " + std::to_string(particles) +
                         " particles (rows x cols of the scene)");
  ViewerFrame frame;
  frame.t = t;
  frame.positions.resize(3 * static_cast<size_t>(particles));
  for (int i = 0; i < particles; ++i) {
    if (table.at(i, 0) != i)
      throw InputError(table.file(), "line " + std::to_string(i + 2),
                       "expected particle " + std::to_string(i));
    for (int k = 0; k < 3; ++k) frame.positions[3 * i + k] = static_cast<float>(table.at(i, 1 + k));
    if (table.at(i, 4) != 0.0) frame.fixed.push_back(i);
  }
  return frame;
}

bool finite_number(const nlohmann::json& j) { return j.is_number() && std::isfinite(j.get<double>()); }

// A file of rows cut at a line's end (a full disk, `head`) is named: rows_short_of_end's rule.
void check_rows_reach_end(const CsvTable& table, const std::vector<double>& times,
                          const nlohmann::json& summary) {
  const std::string cut = rows_short_of_end(
      times.empty() ? std::nullopt : std::optional<double>(times.back()), summary);
  if (!cut.empty()) throw InputError(table.file(), "", cut);
}

void read_dummy(const fs::path& file, ViewerRun& run) {
  const CsvTable table(file, {"section", "point", "x", "y", "z"});
  // Sections and points count from 0, and their product is the row count: neither exceeds it.
  for (int r = 0; r < table.rows(); ++r) {
    run.dummy_sections = std::max(run.dummy_sections, table.integer(r, 0, 0, table.rows() - 1) + 1);
    run.dummy_points = std::max(run.dummy_points, table.integer(r, 1, 0, table.rows() - 1) + 1);
    for (int k = 0; k < 3; ++k)
      run.dummy_positions.push_back(coordinate(table, r, 2 + k));
  }
  if (static_cast<long long>(run.dummy_sections) * run.dummy_points != table.rows())
    throw InputError(
        table.file(), "",
        "sections x points is not the number of rows (" + std::to_string(table.rows()) + ")");
  // A file cut at a section's end still has whole sections: the summary counts them all.
  const nlohmann::json& count = run.summary.value("object_particles", nlohmann::json());
  if (count.is_number() && count != table.rows())
    throw InputError(table.file(), "",
                     fmt::format("{} rows, but summary.json has object_particles {}: the file is "
                                 "cut", table.rows(), count.dump()));
}

void read_hands(const fs::path& file, ViewerRun& run, int particles) {
  const CsvTable table(file, {"t", "available", "x", "y", "z", "candidate", "held"}, {"hand"});
  for (int r = 0; r < table.rows(); ++r) {
    const std::string& name = table.text(r, 0);
    // The page draws two hands; a third name would be a third track it has no colour for.
    if (name != "left" && name != "right")
      throw InputError(table.file(), table.line(r),
                       "column 'hand' is '" + name + "', expected left or right");
    auto hand = std::find_if(run.hands.begin(), run.hands.end(),
                             [&](const ViewerHand& h) { return h.name == name; });
    if (hand == run.hands.end()) {
      run.hands.push_back(ViewerHand{name, {}, {}, {}, {}, {}});
      hand = run.hands.end() - 1;
    }
    const double t = table.finite(r, 0);
    if (!hand->t.empty()) check_time_increases(table, r, t, hand->t.back());
    hand->t.push_back(t);
    hand->available.push_back(table.integer(r, 1, 0, 1));
    for (int k = 0; k < 3; ++k) hand->positions.push_back(coordinate(table, r, 2 + k));
    // A particle index, -1 for none.
    hand->candidate.push_back(table.integer(r, 5, -1, particles - 1));
    hand->held.push_back(table.integer(r, 6, -1, particles - 1));
  }
  // A run writes rows of both hands from its start: a header alone is a file cut too.
  if (run.hands.empty()) check_rows_reach_end(table, {}, run.summary);
  for (const ViewerHand& hand : run.hands) check_rows_reach_end(table, hand.t, run.summary);
}

void read_energy(const fs::path& file, ViewerRun& run) {
  const CsvTable table(file, {"t", "kinetic", "total"});
  for (int r = 0; r < table.rows(); ++r) {
    const double t = table.finite(r, 0);
    if (r > 0) check_time_increases(table, r, t, run.energy_t.back());
    run.energy_t.push_back(t);
    run.energy_kinetic.push_back(table.finite(r, 1));
    run.energy_total.push_back(table.finite(r, 2));
  }
  check_rows_reach_end(table, run.energy_t, run.summary);
}

// The summary.json fields the page shows, each of its type (drapelab run writes them so): a
// damaged one is named here, where the page would throw at load and stay blank (an event
// without a numeric t) or view would stop on nlohmann's message naming no file.
void check_page_fields(const nlohmann::json& summary, const std::string& file) {
  // A field the page reads, when present, must satisfy `ok` (absent ones it does without).
  using Check = bool (*)(const nlohmann::json&);
  const auto expect = [&](const nlohmann::json& object, const std::string& key,
                          const std::string& field, Check ok, const char* expected) {
    if (object.contains(key) && !ok(object[key]))
      throw InputError(file, field, std::string("expected ") + expected);
  };
  const Check number = finite_number;
  const Check string = [](const nlohmann::json& j) { return j.is_string(); };
  for (const char* key : {"status", "integrator"}) expect(summary, key, key, string, "a string");
  expect(summary, "table", "table",
         [](const nlohmann::json& j) { return j.is_string() || j.is_null(); }, "a string or null");
  // The time slider spans them: a negative length has no frame to show.
  for (const char* key : {"duration", "sim_time"})
    expect(summary, key, key, [](const nlohmann::json& j) { return finite_number(j) && j >= 0.0; },
           "a finite number, 0 or more");
  expect(summary, "dt", "dt",
         [](const nlohmann::json& j) { return j.is_null() || (finite_number(j) && j > 0.0); },
         "a finite number above 0, or null");
  expect(summary, "adaptive", "adaptive", [](const nlohmann::json& j) { return j.is_boolean(); },
         "true or false");
  const nlohmann::json& scene = summary["scene"];
  expect(scene, "description", "scene.description", string, "a string");
  const nlohmann::json& events = summary["events"];
  if (!events.is_array()) throw InputError(file, "events", "expected an array");
  for (std::size_t k = 0; k < events.size(); ++k) {
    const std::string field = "events[" + std::to_string(k) + "]";
    const nlohmann::json& e = events[k];
    if (!e.is_object()) throw InputError(file, field, "expected an event (an object)");
    if (!e.contains("t") || !number(e["t"])) throw InputError(file, field + ".t", "expected a finite number");
    if (!e.contains("type") || !e["type"].is_string())
      throw InputError(file, field + ".type", "expected a string");
    for (const char* key : {"key", "hand"}) expect(e, key, field + "." + key, string, "a string");
    for (const char* key : {"particle", "object_particle"})
      expect(e, key, field + "." + key,
             [](const nlohmann::json& j) { return j.is_number_integer(); }, "an integer");
  }
}

// The status of `path`, an InputError naming it when it cannot be known (a symbolic link
// loop, no permission) rather than the filesystem's raw exception; a missing path is not_found.
fs::file_status readable_status(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && status.type() != fs::file_type::not_found)
    throw InputError(path.string(), "", "cannot be read: " + ec.message());
  return status;
}

// Whether the run wrote `name` into `dir`: a regular file. A missing one is a file the run did
// not write; anything else in its place (a folder, a named pipe, which would block the read for
// ever) is an error naming it, not a file taken as absent.
bool has_run_file(const fs::path& dir, const std::string& name) {
  const fs::path path = dir / name;
  const fs::file_status status = readable_status(path);
  if (status.type() == fs::file_type::not_found) return false;
  if (!fs::is_regular_file(status))
    throw InputError(path.string(), "", "not a regular file (a run writes " + name + " as one)");
  return true;
}

// A trace cut at a frame boundary (a full disk, a killed copy) still has whole frames: it must
// reach the run's end, its last frame within one trace interval of the summary's sim_time, as
// the run writes a frame at every multiple of the interval (docs/outputs.md, trace.csv). A run
// that stopped (diverged, failed) traced nothing of its last step: one step_max more.
void check_trace_reaches_end(const std::vector<ViewerFrame>& frames, const nlohmann::json& summary,
                             const fs::path& file) {
  const nlohmann::json* interval = nullptr;
  if (summary["scene"].contains("output") && summary["scene"]["output"].is_object() &&
      summary["scene"]["output"].contains("trace_interval"))
    interval = &summary["scene"]["output"]["trace_interval"];
  if (!summary.contains("sim_time") || !summary["sim_time"].is_number() || !interval ||
      !interval->is_number())
    return;  // a summary of another kind (the checks above need only the grid)
  const double end = summary["sim_time"].get<double>(), step = interval->get<double>();
  const double last = frames.empty() ? -1.0 : frames.back().t;
  const double tolerance = 1e-9 * std::max(1.0, std::abs(end));
  double untraced = 0.0;
  if (summary.value("status", "") != "ok" && summary.contains("step_max") &&
      summary["step_max"].is_number())
    untraced = summary["step_max"].get<double>();
  if (!(step > 0.0) || last < end - step - untraced - tolerance || last > end + tolerance)
    throw InputError(file.string(), "",
                     "the frames end at t = " + std::to_string(last) + " s, but the run (summary.json: "
                     "sim_time " + std::to_string(end) + " s, output.trace_interval " +
                     std::to_string(step) + " s) wrote frames up to its end: the file is cut");
}

}  // namespace

ViewerRun read_viewer_run(const fs::path& dir) {
  ViewerRun run;
  run.name = fs::absolute(dir).lexically_normal().filename().string();
  if (run.name.empty())
    run.name = fs::absolute(dir).lexically_normal().parent_path().filename().string();
  if (!fs::is_directory(readable_status(dir))) throw InputError(dir.string(), "", "not a folder");
  const fs::path summary_file = dir / "summary.json";
  if (!fs::is_regular_file(readable_status(summary_file)))
    throw InputError(dir.string(), "",
                     "not a run folder: no summary.json (drapelab run writes it)");
  run.summary = read_json_file(summary_file.string());
  const std::string sfile = summary_file.string();
  if (!run.summary.is_object() || !run.summary.contains("scene") ||
      !run.summary["scene"].is_object() || !run.summary["scene"].contains("cloth"))
    throw InputError(sfile, "scene.cloth", "missing: the scene as run is needed for the grid");
  const nlohmann::json& cloth = run.summary["scene"]["cloth"];
  run.rows =
      scene_integer(cloth.value("rows", nlohmann::json()), sfile, "scene.cloth.rows", 1, 1 << 15);
  run.cols =
      scene_integer(cloth.value("cols", nlohmann::json()), sfile, "scene.cloth.cols", 1, 1 << 15);
  const int particles = run.rows * run.cols;
  if (run.summary.contains("scene") && run.summary["scene"].contains("pins")) {
    const nlohmann::json& pins = run.summary["scene"]["pins"];
    for (size_t p = 0; p < pins.size(); ++p) {
      const std::string field = "scene.pins[" + std::to_string(p) + "]";
      if (!pins[p].is_array() || pins[p].size() != 2)
        throw InputError(sfile, field, "expected [row, col]");
      scene_integer(pins[p][0], sfile, field, 0, run.rows - 1);
      scene_integer(pins[p][1], sfile, field, 0, run.cols - 1);
    }
  }
  if (!run.summary.contains("events")) run.summary["events"] = nlohmann::json::array();
  check_page_fields(run.summary, sfile);
  // The files the page shows that summary.json says the run wrote: without one the page would
  // show the run without its form, hands or energy, or its final state for a lost trace.
  for (const std::string& name : written_run_files(run.summary, sfile))
    if ((name == "trace.csv" || name == "dummy.csv" || name == "hands.csv" ||
         name == "energy.csv") && !has_run_file(dir, name))
      throw InputError((dir / name).string(), "", "no such file (the run wrote it: summary.json)");

  if (has_run_file(dir, "trace.csv")) {
    run.source = "trace.csv";
    run.frames = read_trace(dir / "trace.csv", particles);
    check_trace_reaches_end(run.frames, run.summary, dir / "trace.csv");
  } else if (has_run_file(dir, "state.csv")) {
    run.source = "state.csv";
    run.frames.push_back(
        read_state(dir / "state.csv", particles, run.summary.value("sim_time", 0.0)));
  }
  // A diverged run's last frames may hold non-finite values: the page shows the finite ones.
  // Before them every frame must be finite (as float: 1e300 is not), or the page's quantisation
  // of all frames would draw nothing.
  const auto finite = [](const auto& frame) {
    return std::all_of(frame.positions.begin(), frame.positions.end(),
                       [](float x) { return std::isfinite(x); });
  };
  if (run.summary.value("status", "") == "diverged")
    while (!run.frames.empty() && !finite(run.frames.back())) run.frames.pop_back();
  for (const auto& frame : run.frames)
    if (!finite(frame))
      throw InputError((dir / run.source).string(), "",
                       fmt::format("the frame at t = {} s has a position that is not finite in "
                                   "single precision (only a diverged run's last frames may)",
                                   frame.t));
  if (run.frames.empty())
    throw InputError(dir.string(), "",
                     "no cloth to show: neither trace.csv nor state.csv with finite positions "
                     "(a diverged run writes no state.csv; rerun with output.trace_interval > 0)");
  if (has_run_file(dir, "dummy.csv")) read_dummy(dir / "dummy.csv", run);
  if (has_run_file(dir, "hands.csv")) read_hands(dir / "hands.csv", run, particles);
  if (has_run_file(dir, "energy.csv")) read_energy(dir / "energy.csv", run);
  return run;
}

}  // namespace drape
