// `hylo._hylo`: the C++ side of the Python package. The pure-Python package (hylo/) gives it
// the signatures users call; this module only converts arrays and errors, releases the GIL
// around long work and calls the libraries as the command line does.
#include "bindings.h"

PYBIND11_MODULE(_hylo, m) {
  m.doc() = "hylo's C++ libraries (use the hylo package, not this module)";
  hylo::python::BindErrors(m);
  hylo::python::BindConfig(m);
  hylo::python::BindClouds(m);
  hylo::python::BindLogs(m);
  hylo::python::BindRuns(m);
  hylo::python::BindPipeline(m);
  hylo::python::BindEval(m);
  hylo::python::BindInspect(m);
}
