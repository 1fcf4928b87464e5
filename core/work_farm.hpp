#pragma once
// Where the items of a map (sweep cells, basin rows) are computed when this process's threads are not the whole
// machine: the CLI's MPI farm (server/cli/mpi_farm.hpp) hands them out to the ranks of an mpirun/srun job as the
// ranks ask for more, because items differ ~100x in cost. The core stays free of MPI: an item's result crosses
// processes as bytes (byte_buffer.hpp) and is delivered, in claim-independent slots, in the process that
// assembles the output, so that output is the same for any number of processes.
#include <functional>
#include <string>
#include <vector>

namespace lienewton {

class WorkFarm {
 public:
  virtual ~WorkFarm() = default;
  // Computes compute(i) for every i of `order` (claim order, most expensive first) in some process, and calls
  // deliver(i, bytes) in this process for each, one call at a time. deliver returning false stops handing out
  // items. Every process of the farm calls run() with the same arguments. Returns true in the process that
  // received the deliveries, false in one that only computed items for it (an MPI worker rank): that process
  // has no result to report.
  virtual bool run(const std::vector<int>& order, const std::function<std::string(int)>& compute,
                   const std::function<bool(int, const std::string&)>& deliver) const = 0;
};

}  // namespace lienewton
