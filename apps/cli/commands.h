#pragma once
// Each `hylo` subcommand lives in its own cmd_<name>.cpp and registers itself on the root app
// through one of these functions. A command reports failure by throwing std::exception with
// a one-line reason; main() prints it and returns a non-zero exit code.

#include <CLI/CLI.hpp>
#include <string>

#include "hylo/io/json.h"

namespace hylo::cli {

void AddInfoCommand(CLI::App& root);
void AddCraftCommand(CLI::App& root);
void AddGroundCommand(CLI::App& root);
void AddMapCommand(CLI::App& root);
void AddLocalizeCommand(CLI::App& root);
void AddTileCommand(CLI::App& root);
void AddSimulateCommand(CLI::App& root);
void AddTraversabilityCommand(CLI::App& root);
void AddInspectCommand(CLI::App& root);
void AddEvalCommand(CLI::App& root);
void AddCompareCommand(CLI::App& root);
void AddDemoCommand(CLI::App& root);
void AddConfigCommand(CLI::App& root);
void AddConvertCommand(CLI::App& root);

/// Writes `summary` to `path` when the user passed --json (path non-empty).
void MaybeWriteJson(const std::string& path, const io::Json& summary);

}  // namespace hylo::cli
