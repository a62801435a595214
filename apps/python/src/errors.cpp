#include "errors.h"

#include "bindings.h"
#include "hylo/common/check.h"

namespace hylo::python {

void BindErrors(py::module_& m) {
  py::exception<run::RunFailed>& run_failed =
      py::register_exception<run::RunFailed>(m, "RunFailed", PyExc_ValueError);
  run_failed.attr("__doc__") =
      "The log was read but gave no trajectory: the pipeline's start failed (the vehicle moved "
      "during the IMU initialisation, no accepted start in the prior map) or no scan was "
      "processed. A ValueError: the data, not the call, is at fault.";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const FileError& e) {
      PyErr_SetString(e.missing() ? PyExc_FileNotFoundError : PyExc_OSError, e.what());
    } catch (const config::ConfigError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const InternalError& e) {
      PyErr_SetString(PyExc_RuntimeError,
                      (std::string("hylo internal error (please report): ") + e.what()).c_str());
    }
  });
}

}  // namespace hylo::python
