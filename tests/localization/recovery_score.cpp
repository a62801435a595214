// A recovery case against the truth: recovered or not, how soon, how honest the poses were.
#include "localization/recovery_score.h"

#include <algorithm>
#include <vector>

#include "estimation/scenario_sinks.h"
#include "hylo/common/time.h"

namespace hylo::testing {
namespace {

using localization::LocalizationEvent;
using odometry::PoseStatus;

bool IsAccept(LocalizationEvent::Kind kind) {
  return kind == LocalizationEvent::Kind::kInitialized ||
         kind == LocalizationEvent::Kind::kRelocalized;
}

bool IsFailedAttempt(LocalizationEvent::Kind kind) {
  return kind == LocalizationEvent::Kind::kRelocalizationFailed ||
         kind == LocalizationEvent::Kind::kSearching ||
         kind == LocalizationEvent::Kind::kInitializationFailed;
}

ScanTimes TimesOf(const std::vector<double>& cpu_ms, const std::vector<double>& wall_ms) {
  ScanTimes t;
  t.scans = cpu_ms.size();
  t.cpu_ms_median = Percentile(cpu_ms, 0.5);
  t.cpu_ms_p99 = Percentile(cpu_ms, 0.99);
  t.wall_ms_median = Percentile(wall_ms, 0.5);
  t.wall_ms_p99 = Percentile(wall_ms, 0.99);
  return t;
}

// Each result: a valid pose within the bound, and its error.
struct ScanCheck {
  int64_t t_ns = 0;
  bool valid = false;
  double error_m = 0.0;
  bool good = false;  // valid and within the bound
};

// The first scan after `from_ns` from which the poses stay good for `stable_ns`, with data
// reaching that far (a scan period short of it, ~0.15 s, is allowed); -1 when none.
int RecoveryIndex(const std::vector<ScanCheck>& scans, int64_t from_ns, int64_t stable_ns) {
  constexpr int64_t kSlackNs = 150'000'000;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    if (scans[i].t_ns < from_ns || !scans[i].good) continue;
    std::size_t j = i;
    while (j < scans.size() && scans[j].t_ns <= scans[i].t_ns + stable_ns && scans[j].good) ++j;
    const bool held = j == scans.size() || scans[j].t_ns > scans[i].t_ns + stable_ns;
    if (held && scans[j - 1].t_ns >= scans[i].t_ns + stable_ns - kSlackNs) {
      return static_cast<int>(i);
    }
    i = j;  // scan j broke the run: no recovery starts before it
  }
  return -1;
}

}  // namespace

RecoveryFigures ScoreRecovery(const RecoveryRun& run, const DriveTruth& truth,
                              const RecoveryScoreOptions& options) {
  const RecoveryCase& c = run.recovery_case();
  const run::Session& session = run.session();
  const auto error_m = [&](int64_t t_ns, const Eigen::Vector3d& p_map) {
    return (p_map + run.origin_world() - truth.PoseAt(t_ns).translation()).norm();
  };
  RecoveryFigures f;
  std::vector<ScanCheck> scans;
  std::vector<double> cpu[2], wall[2];  // [searching, tracking]
  for (const odometry::ScanResult& r : session.results()) {
    ScanCheck s;
    s.t_ns = r.t_ns;
    s.valid = r.pose_status == PoseStatus::kValid;
    s.error_m = error_m(r.t_ns, r.state.p_map_imu);
    s.good = s.valid && s.error_m <= options.max_error_m;
    if (s.valid) f.worst_valid_error_m = std::max(f.worst_valid_error_m, s.error_m);
    if (s.valid && !s.good) ++f.bad_valid_live;
    scans.push_back(s);
    cpu[s.valid].push_back(r.cpu_ms);
    wall[s.valid].push_back(r.total_ms);
  }
  f.searching = TimesOf(cpu[0], wall[0]);
  f.tracking = TimesOf(cpu[1], wall[1]);
  for (const estimation::NavState& x : session.finalized()) {
    const double e = error_m(x.t_ns, x.p_map_imu);
    f.worst_valid_error_m = std::max(f.worst_valid_error_m, e);
    if (e > options.max_error_m) ++f.bad_valid_finalized;
  }
  bool started_before_cut = false;
  for (const LocalizationEvent& e : session.pipeline().events()) {
    if (IsAccept(e.kind)) {
      if (error_m(e.t_ns, e.T_map_imu.translation()) > options.max_error_m) ++f.wrong_accepts;
      if (e.t_ns >= c.return_t_ns) ++f.accepts;
      if (e.kind == LocalizationEvent::Kind::kInitialized && e.t_ns < c.cut_t_ns) {
        started_before_cut = true;
      }
    } else if (IsFailedAttempt(e.kind) && e.t_ns >= c.return_t_ns) {
      ++f.failed_attempts;
    }
  }
  const auto& events = session.pipeline().events();
  if (session.failed()) {
    f.note = session.pipeline().message();
  } else {
    f.note = events.empty()
                 ? "no localization event"
                 : localization::ToString(events.back().kind) + ": " + events.back().message;
  }
  if (c.kind != RecoveryKind::kMovingStart && !started_before_cut) {
    f.skipped = true;
    f.note = "no accepted start before the cut: " + f.note;
    return f;
  }
  const int i = RecoveryIndex(scans, c.return_t_ns, SecondsToNanos(options.stable_s));
  if (i < 0) return f;
  f.recovered = true;
  const int64_t t_ns = scans[i].t_ns;
  f.time_s = NanosToSeconds(t_ns - c.return_t_ns);
  f.distance_m = truth.DistanceAt(t_ns) - truth.DistanceAt(c.return_t_ns);
  std::vector<double> after;
  for (std::size_t j = i; j < scans.size(); ++j) {
    if (scans[j].t_ns > t_ns + SecondsToNanos(options.error_window_s)) break;
    if (scans[j].valid) after.push_back(scans[j].error_m);
  }
  f.error_after_m = Percentile(after, 0.5);
  return f;
}

namespace {

io::Json TimesJson(const ScanTimes& t) {
  return {{"scans", t.scans},
          {"cpu_ms_median", t.cpu_ms_median},
          {"cpu_ms_p99", t.cpu_ms_p99},
          {"wall_ms_median", t.wall_ms_median},
          {"wall_ms_p99", t.wall_ms_p99}};
}

ScanTimes TimesFromJson(const io::Json& j) {
  ScanTimes t;
  t.scans = j.at("scans").get<std::size_t>();
  t.cpu_ms_median = j.at("cpu_ms_median").get<double>();
  t.cpu_ms_p99 = j.at("cpu_ms_p99").get<double>();
  t.wall_ms_median = j.at("wall_ms_median").get<double>();
  t.wall_ms_p99 = j.at("wall_ms_p99").get<double>();
  return t;
}

// NaN is written as null.
double Number(const io::Json& j, const char* key) {
  const io::Json& v = j.at(key);
  return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
}

}  // namespace

io::Json ToJson(const RecoveryFigures& f) {
  io::Json j = io::Json::object();
  j["skipped"] = f.skipped;
  j["recovered"] = f.recovered;
  j["time_s"] = f.time_s;
  j["distance_m"] = f.distance_m;
  j["error_after_m"] = f.error_after_m;
  j["accepts"] = f.accepts;
  j["failed_attempts"] = f.failed_attempts;
  j["wrong_accepts"] = f.wrong_accepts;
  j["bad_valid_live"] = f.bad_valid_live;
  j["bad_valid_finalized"] = f.bad_valid_finalized;
  j["worst_valid_error_m"] = f.worst_valid_error_m;
  j["searching"] = TimesJson(f.searching);
  j["tracking"] = TimesJson(f.tracking);
  j["note"] = f.note;
  return j;
}

RecoveryFigures RecoveryFiguresFromJson(const io::Json& j) {
  RecoveryFigures f;
  f.skipped = j.at("skipped").get<bool>();
  f.recovered = j.at("recovered").get<bool>();
  f.time_s = Number(j, "time_s");
  f.distance_m = Number(j, "distance_m");
  f.error_after_m = Number(j, "error_after_m");
  f.accepts = j.at("accepts").get<int>();
  f.failed_attempts = j.at("failed_attempts").get<int>();
  f.wrong_accepts = j.at("wrong_accepts").get<int>();
  f.bad_valid_live = j.at("bad_valid_live").get<std::size_t>();
  f.bad_valid_finalized = j.at("bad_valid_finalized").get<std::size_t>();
  f.worst_valid_error_m = j.at("worst_valid_error_m").get<double>();
  f.searching = TimesFromJson(j.at("searching"));
  f.tracking = TimesFromJson(j.at("tracking"));
  f.note = j.at("note").get<std::string>();
  return f;
}

}  // namespace hylo::testing
