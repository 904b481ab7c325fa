// The Python module `inertest`: the procedures of GJB 2426A-2004 / IEEE Std 952-1997 and the
// calibration methods on numpy arrays. One wrap function per part of the library.
#include "bindings.h"

PYBIND11_MODULE(inertest, module) {
  module.doc() =
      "inertest: test data processing for gyroscopes and accelerometers (GJB 2426A-2004, IEEE Std 952-1997).\n"
      "Procedures take numpy arrays and return results whose attributes are the JSON names of the CLI's\n"
      "--json output (every figure a Figure with value, unit and uncertainty; to_dict() is that JSON).\n"
      "Bad input raises inertest.Error, a ValueError with the CLI's message.";
  // numpy first, whole, while this thread holds the import lock: pybind11 imports it on the first
  // array it meets, and a first call on several threads at once (the GIL released in each) deadlocked
  // in importlib.
  using namespace inertest::python;
  py::module_::import("numpy");
  wrap_core(module);
  wrap_io(module);
  wrap_procedures(module);
  wrap_misalignment(module);
  wrap_centrifuge(module);
  wrap_allan(module);
  wrap_sim(module);
  wrap_campaign(module);
  wrap_specs(module);
}
