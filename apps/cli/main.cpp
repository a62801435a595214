// hylo: lidar-inertial localization and offline mapping for rough outdoor sites.
// Thin entry point: subcommands register themselves (commands.h); errors end in one line.

#include <cstdio>
#include <exception>

#include "commands.h"

namespace hylo::cli {
void MaybeWriteJson(const std::string& path, const io::Json& summary) {
  if (!path.empty()) io::WriteJsonFile(path, summary);
}
}  // namespace hylo::cli

int main(int argc, char** argv) {
  CLI::App app{"hylo: lidar-inertial localization and offline mapping of rough outdoor sites"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "hylo 0.1.0");
  hylo::cli::AddInfoCommand(app);
  hylo::cli::AddCraftCommand(app);
  hylo::cli::AddGroundCommand(app);
  hylo::cli::AddMapCommand(app);
  hylo::cli::AddLocalizeCommand(app);
  hylo::cli::AddTileCommand(app);
  hylo::cli::AddSimulateCommand(app);
  hylo::cli::AddTraversabilityCommand(app);
  hylo::cli::AddInspectCommand(app);
  hylo::cli::AddEvalCommand(app);
  hylo::cli::AddCompareCommand(app);
  hylo::cli::AddDemoCommand(app);
  hylo::cli::AddConfigCommand(app);
  hylo::cli::AddConvertCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    const auto subcommands = app.get_subcommands();
    std::fprintf(stderr, "hylo %s: error: %s\n",
                 subcommands.empty() ? "" : subcommands.front()->get_name().c_str(), e.what());
    return 1;
  }
  return 0;
}
