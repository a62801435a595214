// hylo.slam / hylo.localize: one log through run::RunLog, the code behind `hylo map` and
// `hylo localize`, so the trajectory and summary are the command's. Files are written only
// when an output folder is given (then exactly the command's files).
#include <pybind11/stl.h>

#include <cmath>

#include "arrays.h"
#include "bindings.h"
#include "config_binding.h"
#include "errors.h"
#include "guess.h"
#include "hylo/run/run_log.h"
#include "progress_relay.h"

namespace hylo::python {
namespace {

struct RunArgs {
  std::string log;
  ConfigHandle config;
  std::string prior_map;  // empty: SLAM
  py::object guess;
  double update_after_s = std::nan("");  // NaN: as configured
  double c2c_max_distance_m = 0.5;
  std::string out_dir;
  std::string label;
};

run::RunRequest Request(const RunArgs& args) {
  run::RunRequest request;
  request.log = args.log;
  request.config = args.config.config;
  request.prior_map = args.prior_map;
  request.out_dir = args.out_dir;
  request.label = args.label;
  request.show_progress = false;  // the Python bar shows it (on_scan)
  if (args.prior_map.empty()) return request;
  localization::LocalizationOptions& localization = request.config.pipeline.localization;
  if (!std::isnan(args.update_after_s)) {
    localization.update_after_s = args.update_after_s;
    std::string why;
    if (!localization.IsValid(&why)) throw std::invalid_argument("update_after_s: " + why);
  }
  if (!(args.c2c_max_distance_m > 0.0)) {
    throw std::invalid_argument("c2c_max_distance_m: must be > 0");
  }
  request.c2c_max_distance_m = args.c2c_max_distance_m;
  request.guess_world_imu = ResolveGuess(args.guess, &request.config);
  return request;
}

py::dict RunLog(const RunArgs& args, py::object progress) {
  run::RunRequest request = Request(args);
  ProgressRelay relay(std::move(progress));
  request.on_scan = [&relay](std::size_t scans) { relay(scans, 0); };
  run::RunResult result;
  {
    py::gil_scoped_release release;
    result = ReadingFiles({args.log, args.prior_map}, [&] { return run::RunLog(request); });
    relay.Flush();
  }
  py::dict out;
  out["summary_json"] = result.summary.dump();
  out["trajectory"] = TrajectoryArray(result.trajectory);
  out["t_ns"] = StampsArray(result.trajectory);
  out["live_trajectory"] = TrajectoryArray(result.live_trajectory);
  out["live_t_ns"] = StampsArray(result.live_trajectory);
  out["ms_per_scan"] = ArrayFromVector(std::move(result.ms_per_scan));
  return out;
}

}  // namespace

void BindRuns(py::module_& m) {
  m.def(
      "run_log",
      [](const std::string& log, const ConfigHandle& config, const std::string& prior_map,
         py::object guess, double update_after_s, double c2c_max_distance_m,
         const std::string& out_dir, const std::string& label, py::object progress) {
        return RunLog(RunArgs{log, config, prior_map, std::move(guess), update_after_s,
                              c2c_max_distance_m, out_dir, label},
                      std::move(progress));
      },
      py::arg("log"), py::arg("config"), py::arg("prior_map"), py::arg("guess"),
      py::arg("update_after_s"), py::arg("c2c_max_distance_m"), py::arg("out_dir"),
      py::arg("label"), py::arg("progress"),
      "One log through the pipeline (hylo.slam / hylo.localize call this).");
}

}  // namespace hylo::python
