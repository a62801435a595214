// The scenario matrix: randomized scenarios (sim/scenario.h) through SLAM and localization with
// both back-ends, each configured from its sensor sheet as a user would (scenario_run.h).
// Prints one line per scenario as it finishes, then per back-end and mode the median and the
// worst over the scenarios (and over the even and the odd numbers apart, for choosing on one
// half and reporting the other), and which scenario is worst. With --explain, the worst
// scenario is run again with one factor eased at a time (a tactical IMU, 1 m/s, no vibration,
// plain mounting, synchronised clocks, a level start, no empty spur, a VLP-16) to tell which
// factor made it worst. Figures are printed and written as JSON (rewritten after every
// scenario, so a long run in the background can be read while it goes), never asserted.
//
//   hylo_scenario_matrix [--scenarios 0-23] [--backends ieskf,sliding_window]
//                        [--no-slam] [--no-localization] [--max-drive-a S] [--max-drive-b S]
//                        [--explain] [--list] [--json PATH] [--preset-dir DIR] [--trace DIR]
//                        [--ease FACTOR]... [--summarize JSON...]
//                        [--variant NAME[@backend,...]:key=value[,key=value...]]...
//                        [--no-default]
// --summarize A.json B.json ... prints and summarizes earlier runs' scenarios as one run (a
// matrix run in parts, e.g. --scenarios 0-11 and 12-23 on two cores), simulating nothing.
// --ease FACTOR sets that factor to its easy value in every scenario (e.g. synchronised clocks
// throughout), to measure how much of the matrix's error one factor accounts for.
// A variant is a configuration to compare with the default on the same simulated data (every
// variant's pipelines are fed by one simulation pass); keys: see kSettings below.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "estimation/scenario_run.h"
#include "hylo/io/json.h"

namespace {

using hylo::estimation::Estimator;
using hylo::odometry::OdometryPipelineOptions;
using hylo::testing::BackendFigures;
using hylo::testing::ModeFigures;
using hylo::testing::ScenarioFigures;
using hylo::testing::Variant;

// The settings a variant may change, by name.
struct Setting {
  const char* key;
  void (*apply)(double value, OdometryPipelineOptions* o);
};
const Setting kSettings[] = {
    {"iterations", [](double v, auto* o) { o->estimator.ieskf.max_iterations = int(v); }},
    {"rematch", [](double v, auto* o) { o->estimator.ieskf.rematch_threshold = v; }},
    {"online_extrinsic", [](double v, auto* o) { o->estimator.ieskf.online_extrinsic = v != 0; }},
    {"lidar_noise", [](double v, auto* o) { o->estimator.lidar_update.lidar_noise_m = v; }},
    {"scan_voxel", [](double v, auto* o) { o->preprocess.scan_voxel_m = v; }},
    {"point_stride", [](double v, auto* o) { o->preprocess.point_stride = int(v); }},
    {"map_voxel", [](double v, auto* o) { o->map.voxel_size_m = v; }},
    {"planarity", [](double v, auto* o) { o->planes.planarity_threshold_m = v; }},
    {"neighbors", [](double v, auto* o) { o->planes.num_neighbors = int(v); }},
    {"line_like_neighbors", [](double v, auto* o) { o->planes.line_like_neighbors = int(v); }},
    {"line_like_ratio", [](double v, auto* o) { o->planes.line_like_ratio = v; }},
    {"gate", [](double v, auto* o) { o->planes.range_gate_factor = v; }},
    {"imu_noise_scale",
     [](double v, auto* o) {
       auto& n = o->imu.noise;
       n.gyro_noise_density *= v;
       n.accel_noise_density *= v;
       n.gyro_bias_random_walk *= v;
       n.accel_bias_random_walk *= v;
     }},
    {"bias_walk_scale",
     [](double v, auto* o) {
       o->imu.noise.gyro_bias_random_walk *= v;
       o->imu.noise.accel_bias_random_walk *= v;
     }},
    {"accel_bias_sigma",
     [](double v, auto* o) { o->initial_uncertainty.accel_bias_sigma_mps2 = v; }},
    {"gyro_bias_sigma",
     [](double v, auto* o) { o->initial_uncertainty.gyro_bias_sigma_radps = v; }},
    {"gravity_sigma", [](double v, auto* o) { o->initial_uncertainty.gravity_sigma_mps2 = v; }},
    {"rotation_sigma", [](double v, auto* o) { o->initial_uncertainty.rotation_sigma_rad = v; }},
    {"init_duration", [](double v, auto* o) { o->init.duration_s = v; }},
    {"standstill", [](double v, auto* o) { o->estimator.standstill.enabled = v != 0; }},
    {"standstill_ratio", [](double v, auto* o) { o->estimator.standstill.max_spread_ratio = v; }},
    {"standstill_speed", [](double v, auto* o) { o->estimator.standstill.max_speed_mps = v; }},
    {"standstill_noise", [](double v, auto* o) { o->estimator.standstill.velocity_noise_mps = v; }},
    {"sw_rounds",
     [](double v, auto* o) { o->estimator.sliding_window.association_rounds = int(v); }},
    {"threads", [](double v, auto* o) { o->threads = int(v); }},
    {"sw_size", [](double v, auto* o) { o->estimator.sliding_window.window_size = int(v); }},
    {"sw_rematch", [](double v, auto* o) { o->estimator.sliding_window.rematch_threshold = v; }},
    {"sw_pairs", [](double v, auto* o) { o->estimator.sliding_window.scan_pairs = v != 0; }},
    {"sw_pair_points", [](double v, auto* o) { o->estimator.sliding_window.pair_points = int(v); }},
    {"sw_iterations",
     [](double v, auto* o) { o->estimator.sliding_window.max_iterations = int(v); }},
};

bool ParseBackends(const std::string& text, std::vector<Estimator::Backend>* out);

// "NAME[@backend,...]:key=value,key=value" -> a variant (false on an unknown key or back-end
// or a malformed value).
bool ParseVariant(const std::string& text, Variant* variant) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  variant->name = text.substr(0, colon);
  const std::size_t at = variant->name.find('@');
  if (at != std::string::npos) {
    if (!ParseBackends(variant->name.substr(at + 1), &variant->backends)) return false;
    variant->name = variant->name.substr(0, at);
  }
  std::vector<std::pair<const Setting*, double>> changes;
  std::size_t start = colon + 1;
  while (start < text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) return false;
    const Setting* setting = nullptr;
    for (const Setting& s : kSettings) {
      if (item.substr(0, eq) == s.key) setting = &s;
    }
    char* end = nullptr;
    const double value = std::strtod(item.c_str() + eq + 1, &end);
    if (setting == nullptr || end == item.c_str() + eq + 1 || *end != '\0') return false;
    changes.push_back({setting, value});
    start = comma + 1;
  }
  if (changes.empty()) return false;
  variant->adjust = [changes](OdometryPipelineOptions* o) {
    for (const auto& [setting, value] : changes) setting->apply(value, o);
  };
  return true;
}

struct Args {
  std::vector<uint64_t> scenarios;
  std::vector<Estimator::Backend> backends = {Estimator::Backend::kIeskf,
                                              Estimator::Backend::kSlidingWindow};
  bool slam = true, localization = true, explain = false, list = false;
  double max_drive_a_s = -1.0, max_drive_b_s = -1.0;
  std::string json_path = "scenario_matrix.json", preset_dir = HYLO_PRESET_DIR, trace_dir;
  std::vector<Variant> variants = {Variant()};   // "default" first unless --no-default
  std::vector<hylo::sim::ScenarioFactor> eased;  // factors eased in every scenario
  std::vector<std::string> summarize;            // JSON files of earlier runs to summarize
};

// "0-5,8,10-12" -> 0 1 2 3 4 5 8 10 11 12.
bool ParseList(const std::string& text, std::vector<uint64_t>* out) {
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    const std::size_t dash = part.find('-');
    char* end = nullptr;
    const uint64_t lo = std::strtoull(part.c_str(), &end, 10);
    const uint64_t hi =
        dash == std::string::npos ? lo : std::strtoull(part.c_str() + dash + 1, &end, 10);
    if (part.empty() || end == part.c_str() || hi < lo) return false;
    for (uint64_t n = lo; n <= hi; ++n) out->push_back(n);
    start = comma + 1;
  }
  return !out->empty();
}

bool ParseBackends(const std::string& text, std::vector<Estimator::Backend>* out) {
  out->clear();
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    Estimator::Backend b;
    if (!hylo::estimation::ParseBackend(text.substr(start, comma - start), &b)) return false;
    out->push_back(b);
    start = comma + 1;
  }
  return !out->empty();
}

bool Parse(int argc, char** argv, Args* args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has = i + 1 < argc;
    if (a == "--scenarios" && has) {
      if (!ParseList(argv[++i], &args->scenarios)) return false;
    } else if (a == "--backends" && has) {
      if (!ParseBackends(argv[++i], &args->backends)) return false;
    } else if (a == "--no-slam") {
      args->slam = false;
    } else if (a == "--no-localization") {
      args->localization = false;
    } else if (a == "--explain") {
      args->explain = true;
    } else if (a == "--list") {
      args->list = true;
    } else if (a == "--max-drive-a" && has) {
      args->max_drive_a_s = std::atof(argv[++i]);
    } else if (a == "--max-drive-b" && has) {
      args->max_drive_b_s = std::atof(argv[++i]);
    } else if (a == "--json" && has) {
      args->json_path = argv[++i];
    } else if (a == "--preset-dir" && has) {
      args->preset_dir = argv[++i];
    } else if (a == "--trace" && has) {
      args->trace_dir = argv[++i];
    } else if (a == "--ease" && has) {
      bool known = false;
      for (const hylo::sim::ScenarioFactor factor : hylo::sim::AllScenarioFactors()) {
        if (ToString(factor) == argv[i + 1]) {
          args->eased.push_back(factor);
          known = true;
        }
      }
      if (!known) {
        std::fprintf(stderr, "--ease: unknown factor '%s'\n", argv[i + 1]);
        return false;
      }
      ++i;
    } else if (a == "--summarize" && has) {
      while (i + 1 < argc && std::strncmp(argv[i + 1], "--", 2) != 0) {
        args->summarize.push_back(argv[++i]);
      }
      if (args->summarize.empty()) return false;
    } else if (a == "--variant" && has) {
      Variant variant;
      if (!ParseVariant(argv[++i], &variant)) {
        std::fprintf(stderr, "--variant '%s': expected NAME:key=value[,...] with known keys\n",
                     argv[i]);
        return false;
      }
      args->variants.push_back(variant);
    } else if (a == "--no-default") {
      args->variants.erase(args->variants.begin());
    } else {
      std::fprintf(stderr, "unknown or incomplete argument '%s'\n", a.c_str());
      return false;
    }
  }
  if (args->scenarios.empty()) {
    for (uint64_t n = 0; n < 24; ++n) args->scenarios.push_back(n);
  }
  return !args->variants.empty();
}

hylo::testing::ScenarioRunOptions RunOptions(const Args& args) {
  hylo::testing::ScenarioRunOptions o;
  o.preset_dir = args.preset_dir;
  o.backends = args.backends;
  o.variants = args.variants;
  o.slam = args.slam;
  o.localization = args.localization;
  o.trace_dir = args.trace_dir;
  if (!o.trace_dir.empty()) std::filesystem::create_directories(o.trace_dir);
  return o;
}

hylo::sim::Scenario Drawn(uint64_t number, const Args& args) {
  hylo::sim::Scenario s = hylo::sim::DrawScenario(number);
  if (args.max_drive_a_s > 0) s.max_drive_a_s = args.max_drive_a_s;
  if (args.max_drive_b_s > 0) s.max_drive_b_s = args.max_drive_b_s;
  for (const hylo::sim::ScenarioFactor factor : args.eased) s = Eased(s, factor);
  return s;
}

// The figure a mode is judged by: SLAM end drift (%), localization ATE (m); failures are worst.
double Key(const ModeFigures& f, bool slam) {
  if (f.failed) return std::numeric_limits<double>::infinity();
  return slam ? f.end_drift_percent : f.ate_m;
}

std::string Cell(const ModeFigures& f, bool slam) {
  if (!f.ran) return "-";
  char text[128];
  if (f.failed) {
    std::snprintf(text, sizeof(text), "FAILED (%s)", f.message.substr(0, 60).c_str());
  } else if (slam) {
    std::snprintf(text, sizeof(text), "%5.2f cm %5.3f %% %5.1f ms", 100 * f.ate_m,
                  f.end_drift_percent, f.cpu_ms_median);
  } else {
    std::snprintf(text, sizeof(text), "%5.2f cm %5.1f ms", 100 * f.ate_m, f.cpu_ms_median);
  }
  return text;
}

void PrintScenario(const ScenarioFigures& f) {
  std::printf("#%-3llu %s; start tilt %.1f deg; sim %.0f s CPU\n",
              static_cast<unsigned long long>(f.number), f.summary.c_str(), f.start_tilt_deg,
              f.sim_cpu_s);
  for (const BackendFigures& run : f.runs) {
    const std::string name = run.variant + " " + hylo::estimation::ToString(run.backend);
    std::printf("     %-26s SLAM ATE/drift/CPU %-32s  localization ATE/CPU %s\n", name.c_str(),
                Cell(run.slam, true).c_str(), Cell(run.localization, false).c_str());
  }
  std::fflush(stdout);
}

double Median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Median and worst of one variant, back-end and mode over a subset of the scenarios.
struct Stats {
  std::size_t count = 0, failed = 0;
  double ate_median = std::nan(""), ate_worst = std::nan("");
  double ate_live_median = std::nan("");  // the live states'
  double drift_median = std::nan(""), drift_worst = std::nan("");
  double cpu_median = std::nan(""), cpu_worst = std::nan("");
  uint64_t worst_number = 0;
  double worst_key = -1.0;
};

const ModeFigures& Mode(const BackendFigures& run, bool slam) {
  return slam ? run.slam : run.localization;
}

Stats Summarize(const std::vector<ScenarioFigures>& all, std::size_t run_index, bool slam,
                int parity) {
  Stats s;
  std::vector<double> ate, ate_live, drift, cpu;
  for (const ScenarioFigures& f : all) {
    if (parity >= 0 && static_cast<int>(f.number % 2) != parity) continue;
    if (run_index >= f.runs.size() || !Mode(f.runs[run_index], slam).ran) continue;
    const ModeFigures& m = Mode(f.runs[run_index], slam);
    ++s.count;
    if (Key(m, slam) > s.worst_key) {
      s.worst_key = Key(m, slam);
      s.worst_number = f.number;
    }
    if (m.failed) {
      ++s.failed;
      continue;
    }
    ate.push_back(m.ate_m);
    if (!std::isnan(m.ate_live_m)) ate_live.push_back(m.ate_live_m);
    drift.push_back(m.end_drift_percent);
    cpu.push_back(m.cpu_ms_median);
  }
  if (ate.empty()) return s;
  s.ate_median = Median(ate);
  s.ate_worst = *std::max_element(ate.begin(), ate.end());
  s.ate_live_median = Median(ate_live);
  s.drift_median = Median(drift);
  s.drift_worst = *std::max_element(drift.begin(), drift.end());
  s.cpu_median = Median(cpu);
  s.cpu_worst = *std::max_element(cpu.begin(), cpu.end());
  return s;
}

hylo::io::Json StatsJson(const Stats& s, bool slam) {
  hylo::io::Json j = hylo::io::Json::object();
  j["scenarios"] = s.count;
  j["failed"] = s.failed;
  j["ate_median_m"] = s.ate_median;
  j["ate_worst_m"] = s.ate_worst;
  j["ate_live_median_m"] = s.ate_live_median;
  if (slam) {
    j["drift_median_percent"] = s.drift_median;
    j["drift_worst_percent"] = s.drift_worst;
  }
  j["cpu_ms_median"] = s.cpu_median;
  j["cpu_ms_worst"] = s.cpu_worst;
  j["worst_scenario"] = static_cast<unsigned long long>(s.worst_number);
  return j;
}

std::string Percent(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f %%", value);
  return text;
}

// What the worst scenario of a row is and what its error looks like: the drift's horizontal
// part points at heading or scale, its vertical part at tilt or gravity; degenerate scans at
// the geometry. (--explain tells which scenario factor made it worst.)
void PrintWorst(const std::vector<ScenarioFigures>& all, std::size_t run_index, bool slam,
                uint64_t number) {
  for (const ScenarioFigures& f : all) {
    if (f.number != number || run_index >= f.runs.size()) continue;
    const BackendFigures& run = f.runs[run_index];
    const ModeFigures& m = Mode(run, slam);
    std::printf("  worst %s %s: #%llu %s: ", hylo::estimation::ToString(run.backend).c_str(),
                slam ? "SLAM" : "localization", static_cast<unsigned long long>(number),
                f.summary.c_str());
    if (m.failed) {
      std::printf("FAILED: %s\n", m.message.c_str());
    } else {
      std::printf(
          "ATE %.2f cm (max %.2f), rotation %.2f deg, end drift %.3f %% of %.0f m "
          "(horizontal %.3f m, vertical %+.3f m), %zu of %zu scans degenerate\n",
          100 * m.ate_m, 100 * m.ate_max_m, m.rotation_rmse_deg, m.end_drift_percent, m.path_m,
          m.end_drift_xy_m, m.end_drift_z_m, m.degenerate, m.scans);
    }
  }
}

// Each back-end's ATE over the filter's on the same scenario and variant (finalized and live
// states), median and worst over the scenarios: what a smoother must show against the filter.
void PrintRatiosToFilter(const std::vector<ScenarioFigures>& all, const Args& args,
                         hylo::io::Json* summary) {
  const std::vector<BackendFigures>& runs = all.front().runs;
  bool header = false;
  const char* parity_names[3] = {"all", "even", "odd"};
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (runs[r].backend == Estimator::Backend::kIeskf) continue;
    // The filter of the same variant, else the first filter run (the same simulated data).
    std::size_t filter = runs.size();
    for (std::size_t k = runs.size(); k-- > 0;) {
      if (runs[k].backend != Estimator::Backend::kIeskf) continue;
      if (filter == runs.size() || runs[k].variant == runs[r].variant) filter = k;
    }
    if (filter == runs.size()) continue;
    for (const bool slam : {true, false}) {
      if (slam ? !args.slam : !args.localization) continue;
      for (int parity = -1; parity <= 1; ++parity) {
        std::vector<double> finalized, live;
        for (const ScenarioFigures& f : all) {
          if (parity >= 0 && static_cast<int>(f.number % 2) != parity) continue;
          const ModeFigures& m = Mode(f.runs[r], slam);
          const ModeFigures& reference = Mode(f.runs[filter], slam);
          if (!m.ran || !reference.ran || m.failed || reference.failed) continue;
          finalized.push_back(m.ate_m / reference.ate_m);
          if (!std::isnan(m.ate_live_m)) live.push_back(m.ate_live_m / reference.ate_m);
        }
        if (finalized.empty()) continue;
        if (!header) {
          std::printf(
              "\n| variant | back-end | mode | scenarios | ATE / filter's, finalized median | "
              "worst | live median | worst |\n|---|---|---|---|---|---|---|---|\n");
          header = true;
        }
        const std::string name = hylo::estimation::ToString(runs[r].backend);
        std::string mode = slam ? "SLAM" : "localization";
        if (parity >= 0) mode += std::string(" (") + parity_names[parity + 1] + ")";
        const double finalized_worst = *std::max_element(finalized.begin(), finalized.end());
        const double live_worst =
            live.empty() ? std::nan("") : *std::max_element(live.begin(), live.end());
        std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %.3f |\n", runs[r].variant.c_str(),
                    name.c_str(), mode.c_str(), finalized.size(), Median(finalized),
                    finalized_worst, Median(live), live_worst);
        hylo::io::Json& j = (*summary)[runs[r].variant][name][slam ? "slam" : "localization"]
                                      [parity_names[parity + 1]];
        j["ate_over_filter_median"] = Median(finalized);
        j["ate_over_filter_worst"] = finalized_worst;
        j["ate_live_over_filter_median"] = Median(live);
      }
    }
  }
}

hylo::io::Json PrintSummary(const std::vector<ScenarioFigures>& all, const Args& args) {
  hylo::io::Json summary = hylo::io::Json::object();
  std::printf(
      "\n| variant | back-end | mode | scenarios | failed | ATE median | ATE worst | "
      "live ATE median | drift median | drift worst | CPU ms/scan median | worst scenario |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const char* parity_names[3] = {"all", "even", "odd"};
  const std::vector<BackendFigures>& runs = all.front().runs;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::string name = hylo::estimation::ToString(runs[r].backend);
    for (const bool slam : {true, false}) {
      if (slam ? !args.slam : !args.localization) continue;
      for (int parity = -1; parity <= 1; ++parity) {
        const Stats s = Summarize(all, r, slam, parity);
        if (s.count == 0) continue;
        std::string mode = slam ? "SLAM" : "localization";
        if (parity >= 0) mode += std::string(" (") + parity_names[parity + 1] + ")";
        std::printf(
            "| %s | %s | %s | %zu | %zu | %.2f cm | %.2f cm | %.2f cm | %s | %s | %.1f | #%llu |\n",
            runs[r].variant.c_str(), name.c_str(), mode.c_str(), s.count, s.failed,
            100 * s.ate_median, 100 * s.ate_worst, 100 * s.ate_live_median,
            slam ? Percent(s.drift_median).c_str() : "-",
            slam ? Percent(s.drift_worst).c_str() : "-", s.cpu_median,
            static_cast<unsigned long long>(s.worst_number));
        summary[runs[r].variant][name][slam ? "slam" : "localization"][parity_names[parity + 1]] =
            StatsJson(s, slam);
      }
    }
  }
  PrintRatiosToFilter(all, args, &summary);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (const bool slam : {true, false}) {
      if (slam ? !args.slam : !args.localization) continue;
      const Stats s = Summarize(all, r, slam, -1);
      if (s.count > 0) PrintWorst(all, r, slam, s.worst_number);
    }
  }
  std::fflush(stdout);
  return summary;
}

// The worst scenario of a mode (over the first variant's back-ends) run again with one factor
// eased at a time, with the back-end that did worst.
hylo::io::Json Explain(const std::vector<ScenarioFigures>& all, const Args& args, bool slam) {
  hylo::io::Json j = hylo::io::Json::object();
  double worst = -1.0;
  const ScenarioFigures* scenario = nullptr;
  const BackendFigures* run = nullptr;
  for (const ScenarioFigures& f : all) {
    for (const BackendFigures& r : f.runs) {
      if (r.variant == args.variants.front().name && Mode(r, slam).ran &&
          Key(Mode(r, slam), slam) > worst) {
        worst = Key(Mode(r, slam), slam);
        scenario = &f;
        run = &r;
      }
    }
  }
  if (scenario == nullptr) return j;
  const char* figure = slam ? "end drift %" : "localization ATE cm";
  const double scale = slam ? 1.0 : 100.0;
  const std::string backend = hylo::estimation::ToString(run->backend);
  std::printf("\nWhy is #%llu the worst (%s, %s: %.3f)? Each factor eased alone:\n",
              static_cast<unsigned long long>(scenario->number), slam ? "SLAM" : "localization",
              backend.c_str(), scale * worst);
  j["scenario"] = static_cast<unsigned long long>(scenario->number);
  j["backend"] = backend;
  j["mode"] = slam ? "slam" : "localization";
  j["figure"] = worst;
  hylo::testing::ScenarioRunOptions options = RunOptions(args);
  options.backends = {run->backend};
  options.variants = {args.variants.front()};
  options.slam = slam;
  options.localization = !slam;
  const hylo::sim::Scenario base = Drawn(scenario->number, args);
  double best = worst;
  std::string best_factor = "none";
  for (const hylo::sim::ScenarioFactor factor : hylo::sim::AllScenarioFactors()) {
    const ScenarioFigures eased = hylo::testing::RunScenario(Eased(base, factor), options);
    const ModeFigures& m = Mode(eased.runs.front(), slam);
    const double key = Key(m, slam);
    std::printf("  %-18s %s = %s\n", ToString(factor).c_str(), figure,
                m.failed ? "FAILED" : std::to_string(scale * key).c_str());
    std::fflush(stdout);
    j["eased"][ToString(factor)] = std::isfinite(key) ? key : std::nan("");
    if (key < best) {
      best = key;
      best_factor = ToString(factor);
    }
  }
  std::printf("  -> the factor whose easing helps most: %s\n", best_factor.c_str());
  j["main_factor"] = best_factor;
  return j;
}

// --summarize: the scenarios of earlier runs' JSON files (e.g. one half of the matrix per
// core), printed and summarized as one run, without simulating anything.
int SummarizeFiles(const Args& args) {
  std::vector<ScenarioFigures> all;
  try {
    for (const std::string& path : args.summarize) {
      const hylo::io::Json j = hylo::io::ReadJsonFile(path);
      if (!j.contains("scenarios") || !j.at("scenarios").is_array()) {
        throw std::runtime_error(path + ": no 'scenarios' array");
      }
      for (const hylo::io::Json& s : j.at("scenarios")) {
        all.push_back(hylo::testing::FromJson(s));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "--summarize: %s\n", e.what());
    return 1;
  }
  if (all.empty()) {
    std::fprintf(stderr, "--summarize: no scenario in the files given\n");
    return 1;
  }
  std::sort(all.begin(), all.end(),
            [](const ScenarioFigures& a, const ScenarioFigures& b) { return a.number < b.number; });
  for (std::size_t k = 1; k < all.size(); ++k) {
    if (all[k].number == all[k - 1].number || all[k].runs.size() != all[0].runs.size()) {
      std::fprintf(stderr, "--summarize: scenario %llu is twice in the files or ran other runs\n",
                   static_cast<unsigned long long>(all[k].number));
      return 1;
    }
  }
  hylo::io::Json out = hylo::io::Json::object();
  for (const ScenarioFigures& f : all) {
    PrintScenario(f);
    out["scenarios"].push_back(hylo::testing::ToJson(f));
  }
  out["summary"] = PrintSummary(all, args);
  hylo::io::WriteJsonFile(args.json_path, out);
  std::printf("\nJSON: %s\n", args.json_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!Parse(argc, argv, &args)) {
    std::fprintf(stderr,
                 "usage: hylo_scenario_matrix [--scenarios 0-23] [--backends ieskf,sliding_window] "
                 "[--no-slam] [--no-localization] [--max-drive-a S] [--max-drive-b S] "
                 "[--explain] [--list] [--json PATH] [--preset-dir DIR] [--trace DIR] "
                 "[--ease FACTOR]... [--summarize JSON...] [--variant NAME:key=value[,...]]... "
                 "[--no-default]\n");
    return 2;
  }
  if (args.list) {  // what the scenarios are, without running them
    for (const uint64_t number : args.scenarios) {
      std::printf("#%-3llu %s\n", static_cast<unsigned long long>(number),
                  Drawn(number, args).Summary().c_str());
    }
    return 0;
  }
  if (!args.summarize.empty()) return SummarizeFiles(args);
  const hylo::testing::ScenarioRunOptions options = RunOptions(args);
  std::vector<ScenarioFigures> all;
  hylo::io::Json out = hylo::io::Json::object();
  out["note"] =
      "CPU times are thread CPU per scan on a shared machine; SLAM ATE after SE(3) alignment, "
      "end drift aligned at the first pose; localization ATE without alignment";
  for (const uint64_t number : args.scenarios) {
    all.push_back(hylo::testing::RunScenario(Drawn(number, args), options));
    PrintScenario(all.back());
    out["scenarios"].push_back(hylo::testing::ToJson(all.back()));
    hylo::io::WriteJsonFile(args.json_path, out);
  }
  out["summary"] = PrintSummary(all, args);
  hylo::io::WriteJsonFile(args.json_path, out);
  if (args.explain) {
    if (args.slam) out["explain"]["slam"] = Explain(all, args, true);
    if (args.localization) out["explain"]["localization"] = Explain(all, args, false);
    hylo::io::WriteJsonFile(args.json_path, out);
  }
  std::printf("\nJSON: %s\n", args.json_path.c_str());
  return 0;
}
