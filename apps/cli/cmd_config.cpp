// `hylo config --doc | --defaults | --check FILE [--out PATH]`: the run configuration's own
// documents. --doc writes the reference (docs/configuration.md is its output), --defaults
// every key at its default as YAML, --check loads a file as a run would and says what is wrong.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "hylo/config/config_doc.h"
#include "hylo/config/run_config.h"
#include "hylo/io/atomic_file.h"

namespace hylo::cli {
namespace {

struct ConfigArgs {
  bool doc = false;
  bool defaults = false;
  std::string check;
  std::string out;  // empty: stdout
};

void Emit(const std::string& text, const std::string& out) {
  if (out.empty()) {
    std::fputs(text.c_str(), stdout);
    return;
  }
  io::WriteFileAtomically(out, text);
  std::fprintf(stderr, "wrote %s\n", out.c_str());
}

void RunConfigCommand(const ConfigArgs& args) {
  if (args.doc + args.defaults + !args.check.empty() != 1) {
    throw std::invalid_argument("give one of --doc, --defaults or --check FILE");
  }
  if (args.doc) return Emit(config::ConfigurationReference(), args.out);
  if (args.defaults) {
    return Emit("# every key at its default (hylo config --defaults)\n" +
                    config::ToYaml(config::RunConfig()),
                args.out);
  }
  const config::RunConfig config = config::LoadRunConfig(args.check);  // ConfigError: the reason
  std::fprintf(stderr, "%s: valid (backend %s, %s)\n", args.check.c_str(),
               config.BackendName().c_str(),
               config.pipeline.imu.enabled ? "with IMU" : "lidar only");
  if (!args.out.empty()) Emit(config::ToYaml(config), args.out);
}

}  // namespace

void AddConfigCommand(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "config", "The run configuration: its reference, its defaults, or a check of a file");
  static ConfigArgs args;
  cmd->add_flag("--doc", args.doc,
                "print the configuration reference (Markdown; docs/configuration.md)");
  cmd->add_flag("--defaults", args.defaults, "print every key at its default (YAML)");
  cmd->add_option("--check", args.check,
                  "load FILE as a run would: exit 0 when it is valid, else name the key and why")
      ->option_text("FILE");
  cmd->add_option("--out", args.out,
                  "write here instead of stdout (with --check: the effective configuration)")
      ->option_text("PATH");
  cmd->callback([] { RunConfigCommand(args); });
}

}  // namespace hylo::cli
