// The recovery benchmark's lines and table.
#include "recovery_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "estimation/scenario_sinks.h"
#include "hylo/common/time.h"

namespace hylo::benchmarks {
namespace {

using testing::RecoveryFigures;
using testing::RecoveryResult;
using testing::RecoveryScenario;

double Median(const std::vector<double>& v) {
  return v.empty() ? std::nan("") : testing::Percentile(v, 0.5);
}

double Worst(const std::vector<double>& v) {
  return v.empty() ? std::nan("") : *std::max_element(v.begin(), v.end());
}

std::string Outcome(const RecoveryFigures& f) {
  char text[160];
  if (f.skipped) return "skipped";
  if (!f.recovered) return "NOT recovered";
  std::snprintf(text, sizeof(text), "recovered in %5.1f s %6.1f m, then %4.1f cm", f.time_s,
                f.distance_m, 100.0 * f.error_after_m);
  return text;
}

}  // namespace

void PrintCases(const RecoveryScenario& s) {
  std::printf("#%-3llu %s; drive %.0f m, %.0f s; %.0f s CPU%s\n",
              static_cast<unsigned long long>(s.number), s.summary.c_str(), s.drive_m, s.drive_s,
              s.cpu_s,
              s.cases_left_out > 0
                  ? (", " + std::to_string(s.cases_left_out) + " case(s) found no place").c_str()
                  : "");
  for (const RecoveryResult& r : s.results) {
    const testing::RecoveryCase& c = r.recovery_case;
    const RecoveryFigures& f = r.figures;
    char gap[64] = "";
    if (c.kind != testing::RecoveryKind::kMovingStart) {
      std::snprintf(gap, sizeof(gap), "%5.1f m (%4.1f s)", c.distance_m,
                    NanosToSeconds(c.return_t_ns - c.cut_t_ns));
    }
    std::printf(
        "  %2d %-12s %-17s at %.1f m/s %-14s %-38s accepts %d (wrong %d), failed attempts %d, "
        "bad valid %zu/%zu, scan wall ms: tracking %.1f, searching %.1f/%.1f (median/p99) | %s\n",
        c.index, testing::ToString(c.kind).c_str(), gap, c.speed_mps,
        estimation::ToString(r.backend).c_str(), Outcome(f).c_str(), f.accepts, f.wrong_accepts,
        f.failed_attempts, f.bad_valid_live, f.bad_valid_finalized, f.tracking.wall_ms_median,
        f.searching.wall_ms_median, f.searching.wall_ms_p99, f.note.substr(0, 160).c_str());
  }
  std::fflush(stdout);
}

RecoveryStats Summarize(const std::vector<RecoveryScenario>& all,
                        estimation::Estimator::Backend backend, const std::string& kind,
                        int parity) {
  RecoveryStats s;
  std::vector<double> time, distance, error, track_wall, track_cpu, track_wall_p99, track_cpu_p99,
      search_wall_median, search_cpu_median, search_wall, search_cpu, ratio;
  for (const RecoveryScenario& scenario : all) {
    if (parity >= 0 && static_cast<int>(scenario.number % 2) != parity) continue;
    for (const RecoveryResult& r : scenario.results) {
      if (r.backend != backend) continue;
      if (!kind.empty() && testing::ToString(r.recovery_case.kind) != kind) continue;
      const RecoveryFigures& f = r.figures;
      ++s.cases;
      s.wrong_accepts += f.wrong_accepts;
      s.bad_valid_live += f.bad_valid_live;
      s.bad_valid_finalized += f.bad_valid_finalized;
      s.worst_valid_error_m = std::max(s.worst_valid_error_m, f.worst_valid_error_m);
      if (f.tracking.scans > 0) {
        track_wall.push_back(f.tracking.wall_ms_median);
        track_cpu.push_back(f.tracking.cpu_ms_median);
        track_wall_p99.push_back(f.tracking.wall_ms_p99);
        track_cpu_p99.push_back(f.tracking.cpu_ms_p99);
      }
      if (f.searching.scans > 0) {
        search_wall.push_back(f.searching.wall_ms_p99);
        search_cpu.push_back(f.searching.cpu_ms_p99);
        search_wall_median.push_back(f.searching.wall_ms_median);
        search_cpu_median.push_back(f.searching.cpu_ms_median);
        if (f.tracking.scans > 0) {
          ratio.push_back(f.searching.wall_ms_p99 / f.tracking.wall_ms_median);
        }
      }
      if (f.skipped) {
        ++s.skipped;
        continue;
      }
      if (!f.recovered) continue;
      ++s.recovered;
      time.push_back(f.time_s);
      distance.push_back(f.distance_m);
      error.push_back(f.error_after_m);
    }
  }
  const std::size_t counted = s.cases - s.skipped;
  s.recovered_percent = counted > 0 ? 100.0 * double(s.recovered) / double(counted) : std::nan("");
  s.time_median_s = Median(time);
  s.time_p90_s = time.empty() ? std::nan("") : testing::Percentile(time, 0.9);
  s.distance_median_m = Median(distance);
  s.distance_p90_m = distance.empty() ? std::nan("") : testing::Percentile(distance, 0.9);
  s.error_after_median_m = Median(error);
  s.tracking_wall_ms_median = Median(track_wall);
  s.tracking_cpu_ms_median = Median(track_cpu);
  s.tracking_wall_ms_p99 = Median(track_wall_p99);
  s.tracking_cpu_ms_p99 = Median(track_cpu_p99);
  s.searching_wall_ms_median = Median(search_wall_median);
  s.searching_cpu_ms_median = Median(search_cpu_median);
  s.searching_wall_ms_p99 = Median(search_wall);
  s.searching_wall_ms_p99_worst = Worst(search_wall);
  s.searching_cpu_ms_p99 = Median(search_cpu);
  s.searching_cpu_ms_p99_worst = Worst(search_cpu);
  s.p99_over_median = Median(ratio);
  s.p99_over_median_worst = Worst(ratio);
  return s;
}

io::Json ToJson(const RecoveryStats& s) {
  return {{"cases", s.cases},
          {"skipped", s.skipped},
          {"recovered", s.recovered},
          {"recovered_percent", s.recovered_percent},
          {"time_median_s", s.time_median_s},
          {"time_p90_s", s.time_p90_s},
          {"distance_median_m", s.distance_median_m},
          {"distance_p90_m", s.distance_p90_m},
          {"error_after_median_m", s.error_after_median_m},
          {"wrong_accepts", s.wrong_accepts},
          {"bad_valid_live", s.bad_valid_live},
          {"bad_valid_finalized", s.bad_valid_finalized},
          {"worst_valid_error_m", s.worst_valid_error_m},
          {"tracking_wall_ms_median", s.tracking_wall_ms_median},
          {"tracking_wall_ms_p99", s.tracking_wall_ms_p99},
          {"searching_wall_ms_median", s.searching_wall_ms_median},
          {"searching_wall_ms_p99", s.searching_wall_ms_p99},
          {"searching_wall_ms_p99_worst", s.searching_wall_ms_p99_worst},
          {"tracking_cpu_ms_median", s.tracking_cpu_ms_median},
          {"tracking_cpu_ms_p99", s.tracking_cpu_ms_p99},
          {"searching_cpu_ms_median", s.searching_cpu_ms_median},
          {"searching_cpu_ms_p99", s.searching_cpu_ms_p99},
          {"searching_cpu_ms_p99_worst", s.searching_cpu_ms_p99_worst},
          {"searching_p99_over_tracking_median", s.p99_over_median},
          {"searching_p99_over_tracking_median_worst", s.p99_over_median_worst}};
}

io::Json PrintSummary(const std::vector<RecoveryScenario>& all) {
  std::vector<estimation::Estimator::Backend> backends;
  for (const RecoveryScenario& s : all) {
    for (const RecoveryResult& r : s.results) {
      if (std::find(backends.begin(), backends.end(), r.backend) == backends.end()) {
        backends.push_back(r.backend);
      }
    }
  }
  std::printf(
      "\n| back-end | kind | half | cases (skipped) | recovered | time median / p90 | "
      "distance median / p90 | error after | wrong accepts | bad valid live / final (worst) | "
      "scan wall ms tracking p50 / p99 | searching p50 / p99 (worst p99) | searching p99 / "
      "tracking "
      "p50 (worst) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  io::Json json = io::Json::object();
  const char* halves[] = {"all", "even", "odd"};
  for (const auto backend : backends) {
    const std::string name = estimation::ToString(backend);
    std::vector<std::string> kinds;
    for (const auto kind : testing::AllRecoveryKinds()) kinds.push_back(testing::ToString(kind));
    kinds.push_back("");
    for (const std::string& kind : kinds) {
      for (int parity = -1; parity <= 1; ++parity) {
        const RecoveryStats s = Summarize(all, backend, kind, parity);
        if (s.cases == 0) continue;
        const std::string kind_name = kind.empty() ? "all" : kind;
        json[name][kind_name][halves[parity + 1]] = ToJson(s);
        std::printf(
            "| %s | %s | %s | %zu (%zu) | %.0f %% | %.1f / %.1f s | %.1f / %.1f m | %.1f cm | %zu "
            "| %zu / %zu (%.2f m) | %.1f / %.1f | %.1f / %.1f (%.1f) | %.1f (%.1f) |\n",
            name.c_str(), kind_name.c_str(), halves[parity + 1], s.cases, s.skipped,
            s.recovered_percent, s.time_median_s, s.time_p90_s, s.distance_median_m,
            s.distance_p90_m, 100.0 * s.error_after_median_m, s.wrong_accepts, s.bad_valid_live,
            s.bad_valid_finalized, s.worst_valid_error_m, s.tracking_wall_ms_median,
            s.tracking_wall_ms_p99, s.searching_wall_ms_median, s.searching_wall_ms_p99,
            s.searching_wall_ms_p99_worst, s.p99_over_median, s.p99_over_median_worst);
      }
    }
  }
  std::fflush(stdout);
  return json;
}

}  // namespace hylo::benchmarks
