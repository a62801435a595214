// Session and site files.
#include "hylo/sim_io/session_writer.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "file_sink.h"
#include "hylo/common/time.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/sim_io/reference_outputs.h"
#include "json_parts.h"

namespace hylo::sim {
namespace {

std::string Join(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / name).string();
}

io::Json ManifestJson(const SimulationOptions& options, const SessionSummary& s,
                      const std::string& dir, logs::LogFormat format) {
  io::Json j = io::Json::object();
  j["generator"] = "hylo simulate";
  j["seed"] = static_cast<unsigned long long>(options.seed);
  j["session"] = ToString(s.session);
  j["role"] = s.session == SessionId::kA ? "mapping" : "localization (changed site, annex)";
  j["frames"] = "map (site), imu (body), lidar; T_a_b maps points from b to a";
  j["files"]["bag"] =
      std::filesystem::path(SessionLogPath(dir, s.session, format)).filename().string();
  j["files"]["log_format"] = logs::ToString(format);
  j["files"]["truth_tum"] =
      std::filesystem::path(SessionTruthPath(dir, s.session)).filename().string();
  j["topics"]["imu"] = "/imu";
  j["topics"]["points"] = "/points";
  j["topics"]["point_time_convention"] = "velodyne";
  j["start_t_ns"] = static_cast<long long>(options.StartNs(s.session));
  j["duration_s"] = s.duration_s;
  j["counts"]["imu_samples"] = s.imu_samples;
  j["counts"]["scans"] = s.scans;
  j["counts"]["points"] = s.points;
  j["path_length_m"] = s.path_length_m;
  j["max_tilt_deg"] = s.max_tilt_deg;
  j["T_imu_lidar"] = PoseJson(options.lidar.T_imu_lidar);
  j["lidar_time_offset_ns"] = static_cast<long long>(options.lidar.time_offset_ns);
  // What a run configuration needs to undo it (t_imu = t_lidar + lidar.time_offset_s).
  j["config_lidar_time_offset_s"] = -NanosToSeconds(options.lidar.time_offset_ns);
  j["imu_initial_accel_bias_mps2"] = Vec(s.initial_accel_bias);
  j["imu_initial_gyro_bias_radps"] = Vec(s.initial_gyro_bias);
  j["options"] = OptionsToJson(options);
  return j;
}

}  // namespace

bool SiteOutputOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(reference_spacing_m >= 0.01))
    os << "reference_spacing_m = " << reference_spacing_m << " must be >= 0.01";
  else if (!(slope_resolution_m > 0.0))
    os << "slope_resolution_m = " << slope_resolution_m << " must be > 0";
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

std::string SessionBagPath(const std::string& dir, SessionId s) {
  return Join(dir, "session_" + ToString(s) + ".bag");
}
std::string SessionLogPath(const std::string& dir, SessionId s, logs::LogFormat format) {
  return logs::LogPathFor(Join(dir, "session_" + ToString(s)), format);
}
std::string SessionTruthPath(const std::string& dir, SessionId s) {
  return Join(dir, "session_" + ToString(s) + "_truth.tum");
}
std::string SessionManifestPath(const std::string& dir, SessionId s) {
  return Join(dir, "session_" + ToString(s) + ".json");
}

SessionSummary WriteSession(const SimulationOptions& options, const Site& site, SessionId session,
                            const std::string& dir,
                            const std::function<void(std::size_t, std::size_t)>& progress,
                            logs::LogFormat format) {
  std::filesystem::create_directories(dir);
  const SessionSimulator simulator(options, site, session);
  FileSink sink(SessionLogPath(dir, session, format), BagLayout(), format);
  const SessionSummary summary = simulator.Run(&sink, progress);
  sink.Close();
  io::WriteTum(SessionTruthPath(dir, session), sink.truth());
  io::WriteJsonFile(SessionManifestPath(dir, session), ManifestJson(options, summary, dir, format));
  return summary;
}

void WriteSiteOutputs(const SimulationOptions& options, const Site& site,
                      const SiteOutputOptions& output, const std::string& dir) {
  std::string why;
  if (!output.IsValid(&why)) throw std::invalid_argument("SiteOutputOptions: " + why);
  std::filesystem::create_directories(dir);
  const World world_a(site.terrain, SessionPrimitives(site, SessionId::kA), options.index_cell_m);
  io::WriteCloud(Join(dir, "site_reference.pcd"),
                 ReferenceCloud(site, world_a, output.reference_spacing_m, options.seed),
                 io::CloudEncoding::kBinary);
  WriteSlopeGrid(Join(dir, "site_slope.txt"), site, output.slope_resolution_m);
  io::Json j = io::Json::object();
  j["seed"] = static_cast<unsigned long long>(options.seed);
  j["site_min_m"] = io::Json::array({site.site_min_m.x(), site.site_min_m.y()});
  j["site_max_m"] = io::Json::array({site.site_max_m.x(), site.site_max_m.y()});
  j["annex_min_m"] = io::Json::array({site.annex_min_m.x(), site.annex_min_m.y()});
  j["annex_max_m"] = io::Json::array({site.annex_max_m.x(), site.annex_max_m.y()});
  j["reference_cloud"] = "site_reference.pcd: session A's site, label 0 = ground, 1 = object";
  j["reference_spacing_m"] = output.reference_spacing_m;
  j["slope_grid"] = "site_slope.txt";
  io::Json objects = io::Json::array();
  for (const SiteObject& object : site.objects) {
    Aabb box;
    for (const Primitive& p : object.parts) box.Extend(BoundsOf(p));
    io::Json o = io::Json::object();
    o["kind"] = object.kind;
    o["in_a"] = object.in_a;
    o["in_b"] = object.in_b;
    o["bounds_min_m"] = Vec(box.min);
    o["bounds_max_m"] = Vec(box.max);
    o["primitives"] = object.parts.size();
    objects.push_back(o);
  }
  j["objects"] = objects;
  io::WriteJsonFile(Join(dir, "site.json"), j);
}

}  // namespace hylo::sim
