// Trajectories (TUM files) and their errors: hylo.read_trajectory / write_trajectory and
// hylo.eval.ate / rpe, which compute what `hylo eval ate|rpe` prints, under its JSON keys.
#include <pybind11/stl.h>

#include <cmath>

#include "arrays.h"
#include "bindings.h"
#include "errors.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/trajectory_io.h"

namespace hylo::python {
namespace {

std::vector<evaluation::TimedPose> Timed(const std::vector<io::StampedPose>& poses) {
  std::vector<evaluation::TimedPose> out;
  out.reserve(poses.size());
  for (const io::StampedPose& p : poses) out.push_back({p.t_ns, p.T_world_body()});
  return out;
}

evaluation::AssociationOptions Association(const std::string& method, double max_dt_s,
                                           double max_gap_s) {
  evaluation::AssociationOptions options;
  if (method == "nearest") {
    options.method = evaluation::Association::kNearest;
  } else if (method != "interp") {
    throw std::invalid_argument("association: '" + method + "' is not one of interp, nearest");
  }
  options.max_dt_ns = SecondsToNs(max_dt_s, "max_dt_s");
  options.max_gap_ns = SecondsToNs(max_gap_s, "max_gap_s");
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("bad time association: " + why);
  return options;
}

evaluation::Alignment Alignment(const std::string& name) {
  if (name == "none") return evaluation::Alignment::kNone;
  if (name == "first") return evaluation::Alignment::kFirstPose;
  if (name == "sim3") return evaluation::Alignment::kSim3;
  if (name == "se3") return evaluation::Alignment::kSE3;
  throw std::invalid_argument("align: '" + name + "' is not one of se3, sim3, first, none");
}

// The statistics ATE and RPE share, under `hylo eval`'s JSON keys.
template <class Result>
void AddErrorFields(const Result& r, py::dict* out) {
  py::dict& j = *out;
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

struct Trajectories {
  std::vector<evaluation::TimedPose> estimate, reference;
};

Trajectories Inputs(const py::handle& est, const py::handle& est_t_ns, const py::handle& gt,
                    const py::handle& gt_t_ns) {
  Trajectories t{Timed(PosesFromArray(est, est_t_ns, "est")),
                 Timed(PosesFromArray(gt, gt_t_ns, "gt"))};
  if (t.estimate.empty()) throw std::invalid_argument("est: holds no pose");
  if (t.reference.empty()) throw std::invalid_argument("gt: holds no pose");
  return t;
}

py::dict Ate(const py::handle& est, const py::handle& est_t_ns, const py::handle& gt,
             const py::handle& gt_t_ns, const std::string& align, const std::string& association,
             double max_dt_s, double max_gap_s) {
  evaluation::AteOptions options;
  options.association = Association(association, max_dt_s, max_gap_s);
  options.alignment = Alignment(align);
  const Trajectories t = Inputs(est, est_t_ns, gt, gt_t_ns);
  evaluation::AteResult ate;
  {
    py::gil_scoped_release release;
    ate = evaluation::ComputeAte(t.estimate, t.reference, options);
  }
  if (!ate.ok) throw std::invalid_argument("ate: " + ate.message);
  py::dict j;
  j["metric"] = "ate";
  j["association"] = association;
  j["alignment"] = align;
  j["num_poses"] = ate.num_poses;
  j["num_unmatched"] = ate.num_unmatched;
  j["scale"] = ate.scale;
  AddErrorFields(ate, &j);
  j["path_length_m"] = ate.path_length_m;
  j["end_drift_m"] = ate.end_drift_m;
  j["T_reference_estimate"] = MatrixArray(ate.T_reference_estimate);
  std::vector<double> t_s;
  for (const int64_t t_ns : ate.t_ns) t_s.push_back(static_cast<double>(t_ns) / 1e9);
  j["t_s"] = ArrayFromVector(std::move(t_s));
  j["translation_errors_m"] = ArrayFromVector(std::move(ate.translation_errors_m));
  return j;
}

py::dict Rpe(const py::handle& est, const py::handle& est_t_ns, const py::handle& gt,
             const py::handle& gt_t_ns, double delta, const std::string& delta_unit,
             const std::string& association, double max_dt_s, double max_gap_s) {
  evaluation::RpeOptions options;
  options.association = Association(association, max_dt_s, max_gap_s);
  options.delta = delta;
  if (delta_unit == "m") {
    options.unit = evaluation::DeltaUnit::kMeters;
  } else if (delta_unit != "frames") {
    throw std::invalid_argument("delta_unit: '" + delta_unit + "' is not one of frames, m");
  }
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  const Trajectories t = Inputs(est, est_t_ns, gt, gt_t_ns);
  evaluation::RpeResult rpe;
  {
    py::gil_scoped_release release;
    rpe = evaluation::ComputeRpe(t.estimate, t.reference, options);
  }
  if (!rpe.ok) throw std::invalid_argument("rpe: " + rpe.message);
  py::dict j;
  j["metric"] = "rpe";
  j["association"] = association;
  j["delta"] = delta;
  j["delta_unit"] = delta_unit;
  j["num_poses"] = rpe.num_poses;
  j["num_pairs"] = rpe.num_pairs;
  AddErrorFields(rpe, &j);
  return j;
}

py::tuple ReadTrajectory(const std::string& path) {
  std::vector<io::StampedPose> poses;
  {
    py::gil_scoped_release release;
    poses = ReadingFiles({path}, [&] { return io::ReadTum(path); });
  }
  return py::make_tuple(TrajectoryArray(poses), StampsArray(poses));
}

void WriteTrajectory(const std::string& path, const py::handle& poses, const py::handle& t_ns) {
  const std::vector<io::StampedPose> stamped = PosesFromArray(poses, t_ns, "trajectory");
  py::gil_scoped_release release;
  ReadingFiles({}, [&] { io::WriteTum(path, stamped); });
}

}  // namespace

void BindEval(py::module_& m) {
  const py::none none;
  m.def("_read_trajectory", &ReadTrajectory, py::arg("path"));
  m.def("_write_trajectory", &WriteTrajectory, py::arg("path"), py::arg("poses"),
        py::arg("t_ns") = none);
  m.def("_ate", &Ate, py::arg("est"), py::arg("est_t_ns"), py::arg("gt"), py::arg("gt_t_ns"),
        py::arg("align"), py::arg("association"), py::arg("max_dt_s"), py::arg("max_gap_s"));
  m.def("_rpe", &Rpe, py::arg("est"), py::arg("est_t_ns"), py::arg("gt"), py::arg("gt_t_ns"),
        py::arg("delta"), py::arg("delta_unit"), py::arg("association"), py::arg("max_dt_s"),
        py::arg("max_gap_s"));
}

}  // namespace hylo::python
