#pragma once
// The core's SO(3), SE(3) and SO(n) as stacked NumPy functions of lienewton._lienewton (so3_exp, se3_log, son_dexp,
// ...), for the group classes of lienewton/groups.py.
#include <pybind11/pybind11.h>

namespace lienewton::python {

void bind_groups(pybind11::module_& m);

}  // namespace lienewton::python
