#include "demo_inspection.h"

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "hylo/io/targets_io.h"
#include "hylo/run/inspection_run.h"
#include "hylo/sim/equipment_targets.h"
#include "hylo/sim_io/equipment_targets_io.h"

namespace hylo::cli {

io::Json InspectionStep::ToJson() const {
  io::Json j = io::Json::object();
  j["dir"] = dir;
  j["targets_file"] = targets_csv;
  j["seconds"] = seconds;
  for (const char* key : {"targets", "route", "start", "seconds"}) {
    if (plan.contains(key)) j[std::string("plan_") + key] = plan.at(key);
  }
  io::Json& missed = j["not_planned"] = io::Json::array();
  for (const io::Json& t : plan.value("per_target", io::Json::array())) {
    if (t.at("status") != "planned") {
      missed.push_back(
          {{"id", t.at("id")}, {"status", t.at("status")}, {"reason", t.at("reason")}});
    }
  }
  return j;
}

InspectionStep InspectSite(const sim::Site& site, const evaluation::AteResult& ate_a,
                           const std::string& crafted_map, const std::string& costmap_dir,
                           const std::string& dir) {
  if (!ate_a.ok)
    throw std::runtime_error("session A's alignment to the truth failed: " + ate_a.message);
  const auto start = std::chrono::steady_clock::now();
  InspectionStep step;
  step.dir = dir;
  step.targets_csv = dir + "/targets.csv";
  std::filesystem::create_directories(dir);
  // The map's frame is session A's: its alignment places the site's equipment in it.
  const Eigen::Isometry3d T_map_site = ate_a.T_reference_estimate.inverse();
  io::WriteTargetsCsv(
      step.targets_csv,
      sim::EquipmentAsTargets(sim::EquipmentTargets(site, sim::SessionId::kA), T_map_site));
  const run::InspectionInputs inputs =
      run::ReadInspectionInputs(crafted_map, costmap_dir, step.targets_csv);
  // The route starts where session A started, the map frame's origin (`hylo inspect`'s default).
  const run::InspectionRun plan =
      run::PlanInspectionRun(inputs, Eigen::Vector2d::Zero(), inspection::InspectionOptions());
  run::WriteInspectionRun(dir, inputs, plan);
  step.plan = plan.summary;
  step.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return step;
}

}  // namespace hylo::cli
