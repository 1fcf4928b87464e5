#pragma once
// Include cpp-httplib through this header: httplib.h pulls in <resolv.h>, whose `#define _res` macro breaks
// Eigen's product kernels (they name a parameter _res) in any file that includes Eigen afterwards.
#include <httplib.h>
#undef _res
