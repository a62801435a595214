#pragma once
// The configuration reference (docs/configuration.md), generated from the field list: every
// section and key with its default as a saved configuration writes it, the values an enum
// takes, and the field's description. `hylo config --doc` prints it; a test keeps the
// committed file equal to it.

#include <string>

namespace hylo::config {

/// The whole reference as Markdown.
std::string ConfigurationReference();

}  // namespace hylo::config
