// `hylo eval c2c|ate|rpe`: the evaluation metrics of the paper and of trajectory benchmarks.
//   c2c: cloud-to-cloud distance of A to B (nearest neighbours on an ikd-tree built from B,
//        pairs beyond --max-dist rejected as outliers; Alamanos et al., Table I).
//   ate: absolute trajectory error after alignment (Umeyama SE(3)/Sim(3), first pose, none).
//   rpe: relative pose error over a frame or distance delta.
// Trajectories are TUM or KITTI; the estimate is associated to the reference in time by
// interpolating the reference (default) or by nearest stamp within --max-dt.

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "commands.h"
#include "hylo/common/local_origin.h"
#include "hylo/evaluation/cloud_distance.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::cli {
namespace {

struct TrajectoryArgs {
  std::string est, gt, format = "tum", est_times, gt_times, json, association = "interp";
  double max_dt_s = 0.02;
  double max_gap_s = 1.0;
  double kitti_period_s = 0.1;
};

struct C2cArgs {
  std::string cloud, ref, json;
  double max_dist_m = evaluation::CloudDistanceOptions().max_distance_m;
};

struct AteArgs : TrajectoryArgs {
  std::string align = "se3";
};

struct RpeArgs : TrajectoryArgs {
  double delta = 1.0;
  std::string delta_unit = "frames";
};

int64_t SecondsToNs(double s) { return static_cast<int64_t>(std::llround(s * 1e9)); }

std::vector<evaluation::TimedPose> ReadTrajectory(const std::string& path, const std::string& times,
                                                  const TrajectoryArgs& args) {
  std::vector<io::StampedPose> poses;
  if (args.format == "tum") {
    poses = io::ReadTum(path);
  } else {
    io::KittiTiming timing;
    timing.times_path = times;
    timing.period_s = args.kitti_period_s;
    poses = io::ReadKitti(path, timing);
  }
  if (poses.empty()) throw std::runtime_error("'" + path + "' holds no pose");
  std::vector<evaluation::TimedPose> out;
  for (const io::StampedPose& p : poses) out.push_back({p.t_ns, p.T_world_body()});
  return out;
}

evaluation::AssociationOptions ParseAssociation(const TrajectoryArgs& args) {
  evaluation::AssociationOptions options;
  options.method = args.association == "nearest" ? evaluation::Association::kNearest
                                                 : evaluation::Association::kInterpolate;
  options.max_dt_ns = SecondsToNs(args.max_dt_s);
  options.max_gap_ns = SecondsToNs(args.max_gap_s);
  std::string why;
  if (!options.IsValid(&why)) throw std::runtime_error("bad time association: " + why);
  return options;
}

evaluation::Alignment ParseAlignment(const std::string& name) {
  if (name == "none") return evaluation::Alignment::kNone;
  if (name == "first") return evaluation::Alignment::kFirstPose;
  if (name == "sim3") return evaluation::Alignment::kSim3;
  return evaluation::Alignment::kSE3;
}

void AddInputs(io::Json* json, const TrajectoryArgs& args) {
  (*json)["estimate"] = args.est;
  (*json)["reference"] = args.gt;
  (*json)["format"] = args.format;
  (*json)["association"] = args.association;
  (*json)["max_dt_s"] = args.max_dt_s;
  (*json)["max_gap_s"] = args.max_gap_s;
}

void RunC2c(const C2cArgs& args) {
  const io::CloudFile a = io::ReadCloud(args.cloud);
  const io::CloudFile b = io::ReadCloud(args.ref);
  if (b.positions.empty()) throw std::runtime_error("'" + args.ref + "' holds no point");
  // Both clouds shifted by one origin so that UTM coordinates keep their millimetres in float.
  const Eigen::Vector3d origin = ChooseOrigin(b.positions);
  mapping::IkdTree tree;
  tree.Build(ToLocal(b.positions, origin));
  evaluation::CloudDistanceOptions options;
  options.max_distance_m = args.max_dist_m;
  const evaluation::CloudDistanceSummary s =
      evaluation::CloudToCloudDistance(ToLocal(a.positions, origin), tree, options);
  if (!s.ok) throw std::runtime_error("c2c " + args.cloud + " -> " + args.ref + ": " + s.message);
  std::printf("cloud-to-cloud distance %s -> %s (outliers beyond %.3f m rejected)\n",
              args.cloud.c_str(), args.ref.c_str(), args.max_dist_m);
  std::printf("  %-10s %-10s %-10s %-10s %-10s %-9s %-9s\n", "mean [m]", "std [m]", "median", "rms",
              "max", "inliers", "rejected");
  std::printf("  %-10.4f %-10.4f %-10.4f %-10.4f %-10.4f %-9zu %.2f %%\n", s.mean_m, s.std_m,
              s.median_m, s.rms_m, s.max_m, s.count, 100.0 * s.rejected_fraction);
  io::Json json;
  json["metric"] = "c2c";
  json["cloud"] = args.cloud;
  json["reference"] = args.ref;
  json["max_distance_m"] = args.max_dist_m;
  json["num_points"] = s.num_points;
  json["count"] = s.count;
  json["num_rejected"] = s.num_rejected;
  json["rejected_fraction"] = s.rejected_fraction;
  json["mean_m"] = s.mean_m;
  json["std_m"] = s.std_m;
  json["median_m"] = s.median_m;
  json["rms_m"] = s.rms_m;
  json["max_m"] = s.max_m;
  MaybeWriteJson(args.json, json);
}

void PrintErrorRow(double rmse, double mean, double median, double max, const char* unit,
                   const char* what) {
  std::printf("  %-12s %-10.4f %-10.4f %-10.4f %-10.4f %s\n", what, rmse, mean, median, max, unit);
}

// ATE and RPE results carry the same translation (m) and rotation (deg) statistics under the
// same names; one table and one set of JSON keys for both.
template <typename ErrorResult>
void PrintErrorTable(const ErrorResult& r) {
  std::printf("  %-12s %-10s %-10s %-10s %-10s\n", "", "rmse", "mean", "median", "max");
  PrintErrorRow(r.rmse_m, r.mean_m, r.median_m, r.max_m, "m", "translation");
  PrintErrorRow(r.rotation_rmse_deg, r.rotation_mean_deg, r.rotation_median_deg,
                r.rotation_max_deg, "deg", "rotation");
}

template <typename ErrorResult>
void AddErrorFields(const ErrorResult& r, io::Json* json) {
  io::Json& j = *json;
  j["rmse_m"] = r.rmse_m;
  j["mean_m"] = r.mean_m;
  j["median_m"] = r.median_m;
  j["std_m"] = r.std_m;
  j["max_m"] = r.max_m;
  j["rotation_rmse_deg"] = r.rotation_rmse_deg;
  j["rotation_mean_deg"] = r.rotation_mean_deg;
  j["rotation_median_deg"] = r.rotation_median_deg;
  j["rotation_max_deg"] = r.rotation_max_deg;
}

void RunAte(const AteArgs& args) {
  evaluation::AteOptions options;
  options.association = ParseAssociation(args);
  options.alignment = ParseAlignment(args.align);
  const evaluation::AteResult ate =
      evaluation::ComputeAte(ReadTrajectory(args.est, args.est_times, args),
                             ReadTrajectory(args.gt, args.gt_times, args), options);
  if (!ate.ok) throw std::runtime_error("ate " + args.est + " vs " + args.gt + ": " + ate.message);
  std::printf("ATE %s vs %s: %zu poses (%zu unmatched), alignment %s, scale %.6f, path %.2f m\n",
              args.est.c_str(), args.gt.c_str(), ate.num_poses, ate.num_unmatched,
              args.align.c_str(), ate.scale, ate.path_length_m);
  PrintErrorTable(ate);
  io::Json json;
  json["metric"] = "ate";
  AddInputs(&json, args);
  json["alignment"] = args.align;
  json["num_poses"] = ate.num_poses;
  json["num_unmatched"] = ate.num_unmatched;
  json["scale"] = ate.scale;
  AddErrorFields(ate, &json);
  json["path_length_m"] = ate.path_length_m;
  json["end_drift_m"] = ate.end_drift_m;
  // Row-major, as a 4×4 is read and typed (Eigen stores column-major).
  const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> T = ate.T_reference_estimate.matrix();
  json["T_reference_estimate"] = io::Json(std::vector<double>(T.data(), T.data() + 16));
  MaybeWriteJson(args.json, json);
}

void RunRpe(const RpeArgs& args) {
  evaluation::RpeOptions options;
  options.association = ParseAssociation(args);
  options.delta = args.delta;
  options.unit =
      args.delta_unit == "m" ? evaluation::DeltaUnit::kMeters : evaluation::DeltaUnit::kFrames;
  const evaluation::RpeResult rpe =
      evaluation::ComputeRpe(ReadTrajectory(args.est, args.est_times, args),
                             ReadTrajectory(args.gt, args.gt_times, args), options);
  if (!rpe.ok) throw std::runtime_error("rpe " + args.est + " vs " + args.gt + ": " + rpe.message);
  std::printf("RPE %s vs %s: delta %g %s, %zu pairs over %zu poses\n", args.est.c_str(),
              args.gt.c_str(), args.delta, args.delta_unit.c_str(), rpe.num_pairs, rpe.num_poses);
  PrintErrorTable(rpe);
  io::Json json;
  json["metric"] = "rpe";
  AddInputs(&json, args);
  json["delta"] = args.delta;
  json["delta_unit"] = args.delta_unit;
  json["num_poses"] = rpe.num_poses;
  json["num_pairs"] = rpe.num_pairs;
  AddErrorFields(rpe, &json);
  MaybeWriteJson(args.json, json);
}

void AddTrajectoryOptions(CLI::App* cmd, TrajectoryArgs* args) {
  cmd->add_option("--est", args->est, "estimated trajectory")->required();
  cmd->add_option("--gt", args->gt, "reference (ground-truth) trajectory")->required();
  cmd->add_option("--format", args->format, "trajectory format")
      ->check(CLI::IsMember({"tum", "kitti"}))
      ->capture_default_str();
  cmd->add_option("--est-times", args->est_times, "KITTI: times file of the estimate (s)");
  cmd->add_option("--gt-times", args->gt_times, "KITTI: times file of the reference (s)");
  cmd->add_option("--kitti-period", args->kitti_period_s,
                  "KITTI without times file: seconds between poses")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--assoc", args->association,
                  "time association: interpolate the reference, or nearest stamp")
      ->check(CLI::IsMember({"interp", "nearest"}))
      ->capture_default_str();
  cmd->add_option("--max-dt", args->max_dt_s, "nearest: largest stamp difference, s")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--max-gap", args->max_gap_s,
                  "interp: largest reference gap to interpolate across, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--json", args->json, "write a JSON summary here");
}

}  // namespace

void AddEvalCommand(CLI::App& root) {
  auto* eval = root.add_subcommand("eval", "Evaluation metrics: c2c, ate, rpe");
  eval->require_subcommand(1);

  auto* c2c = eval->add_subcommand("c2c", "Cloud-to-cloud distance of --cloud to --ref");
  static C2cArgs c2c_args;
  c2c->add_option("--cloud", c2c_args.cloud, "cloud A (PCD/PLY/KITTI .bin/LAS)")->required();
  c2c->add_option("--ref", c2c_args.ref, "reference cloud B")->required();
  c2c->add_option("--max-dist", c2c_args.max_dist_m, "outlier threshold, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c2c->add_option("--json", c2c_args.json, "write a JSON summary here");
  c2c->callback([] { RunC2c(c2c_args); });

  auto* ate = eval->add_subcommand("ate", "Absolute trajectory error of --est against --gt");
  static AteArgs ate_args;
  AddTrajectoryOptions(ate, &ate_args);
  ate->add_option("--align", ate_args.align, "alignment before the errors")
      ->check(CLI::IsMember({"se3", "sim3", "first", "none"}))
      ->capture_default_str();
  ate->callback([] { RunAte(ate_args); });

  auto* rpe = eval->add_subcommand("rpe", "Relative pose error of --est against --gt");
  static RpeArgs rpe_args;
  AddTrajectoryOptions(rpe, &rpe_args);
  rpe->add_option("--delta", rpe_args.delta, "pose pair spacing (frames or metres)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  rpe->add_option("--delta-unit", rpe_args.delta_unit, "what --delta counts")
      ->check(CLI::IsMember({"frames", "m"}))
      ->capture_default_str();
  rpe->callback([] { RunRpe(rpe_args); });
}

}  // namespace hylo::cli
