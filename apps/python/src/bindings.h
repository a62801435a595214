#pragma once
// The module's parts: each adds its functions and classes to the module (module.cpp calls
// them in this order, so a later part may name the classes of an earlier one).

#include <pybind11/pybind11.h>

namespace hylo::python {

namespace py = pybind11;

void BindErrors(py::module_& m);    // errors.cpp: the exceptions Python sees
void BindConfig(py::module_& m);    // config_binding.cpp: Config
void BindClouds(py::module_& m);    // cloud_binding.cpp: clouds and the ground filter
void BindLogs(py::module_& m);      // log_binding.cpp: LogReader, ImuSample, Scan
void BindRuns(py::module_& m);      // run_binding.cpp: a log through the pipeline (slam, localize)
void BindPipeline(py::module_& m);  // pipeline_binding.cpp: data from memory, scan by scan
void BindEval(py::module_& m);      // eval_binding.cpp: trajectories, ATE, RPE
void BindInspect(py::module_& m);   // inspect_binding.cpp: inspection planning from files

}  // namespace hylo::python
