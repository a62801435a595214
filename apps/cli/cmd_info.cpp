// `hylo info LOG`: placeholder until the bag and scan-folder readers land (this session).
#include "commands.h"

#include <stdexcept>

namespace hylo::cli {
void AddInfoCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand("info", "Describe a log: a ROS1 bag or a scan folder");
  static std::string path;
  cmd->add_option("LOG", path, "ROS1 bag or scan folder")->required();
  cmd->callback([] { throw std::runtime_error("not implemented yet"); });
}
}  // namespace hylo::cli
