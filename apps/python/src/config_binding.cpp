// Config: a run configuration from a YAML file, YAML text, or (in Python) a dict written as
// YAML. Every way goes through config::ParseRunConfig: the keys, errors and validation are
// those of `hylo map --config`.
#include <fstream>
#include <sstream>

#include "bindings.h"
#include "config_binding.h"
#include "errors.h"

namespace hylo::python {
namespace {

ConfigHandle FromText(const std::string& text, const std::string& source) {
  return ConfigHandle{config::ParseRunConfig(text, source), text, source};
}

ConfigHandle Load(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    std::error_code ec;
    throw FileError("cannot read configuration file '" + path + "'",
                    !std::filesystem::exists(path, ec));
  }
  std::ostringstream text;
  text << file.rdbuf();
  return FromText(text.str(), path);
}

ConfigHandle WithOverrides(const ConfigHandle& base, const std::string& overrides,
                           const std::string& source) {
  const std::string name = base.source + " + " + source;
  return FromText(config::MergeYaml(base.text, overrides, name), name);
}

}  // namespace

void BindConfig(py::module_& m) {
  py::class_<ConfigHandle>(m, "Config",
                           "A run configuration (the YAML of `hylo map --config`), parsed and "
                           "validated. Make one with hylo.load_config(path or dict).")
      .def_static("from_yaml", &FromText, py::arg("text"), py::arg("source") = "<yaml>",
                  "Parses YAML text; ValueError naming `source`, the key path and the reason.")
      .def_static("load", &Load, py::arg("path"),
                  "Reads a YAML file; OSError when it cannot be read, ValueError when invalid.")
      .def("with_overrides", &WithOverrides, py::arg("yaml_text"),
           py::arg("source") = "overrides",
           "A new Config: this one with the keys of `yaml_text` set (maps merged key by key).")
      .def("to_yaml", [](const ConfigHandle& c) { return config::ToYaml(c.config); },
           "The effective configuration, every key with its value (what a run saves).")
      .def_property_readonly("text", [](const ConfigHandle& c) { return c.text; },
                             "The YAML this configuration was parsed from.")
      .def_property_readonly("source", [](const ConfigHandle& c) { return c.source; },
                             "The file (or <dict>) error messages name.")
      .def_property_readonly("backend", [](const ConfigHandle& c) { return c.config.BackendName(); },
                             "ieskf or sliding_window.")
      .def_property_readonly("initial_guess",
                             [](const ConfigHandle& c) { return c.config.initial_guess; },
                             "localization.initial_guess as written ('' = none).")
      .def("__repr__", [](const ConfigHandle& c) {
        return "<hylo.Config " + c.source + " backend=" + c.config.BackendName() + ">";
      });
}

}  // namespace hylo::python
