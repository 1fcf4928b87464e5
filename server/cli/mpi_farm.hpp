#pragma once
// The CLI under mpirun or srun (built with -DLIENEWTON_MPI=ON): every rank runs the same command on the same
// request, rank 0 hands out the map's items (sweep cells, basin rows) one at a time as ranks finish them
// (dynamic: items differ ~100x in cost) and prints the output, which is byte for byte the single-process one.
#include <string>

#include "core/work_farm.hpp"

namespace lienewton::cli {

// MPI_Init_thread / MPI_Finalize for the life of the process, taken only when an MPI launcher started it (a
// plain `lienewton sweep` never touches MPI).
class MpiSession {
 public:
  // True when mpirun (Open MPI's OMPI_COMM_WORLD_SIZE) or Slurm's srun (PMI/PMIx variables) started this process.
  static bool launched_by_mpi();
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank 0's text on every rank (rank 0 alone reads the request from stdin: mpirun forwards stdin to it only).
  std::string broadcast(std::string text) const;

 private:
  int rank_ = 0, size_ = 1;
};

// Rank 0 computes items in a thread of its own while its main thread (the only one that calls MPI) hands items
// out: first two to every other rank (so a rank has its next item while it sends a result), then one per result.
// The other ranks compute what they are sent until told the round is over.
class MpiFarm final : public WorkFarm {
 public:
  explicit MpiFarm(const MpiSession& session) : session_(session) {}
  bool run(const std::vector<int>& order, const std::function<std::string(int)>& compute,
           const std::function<bool(int, const std::string&)>& deliver) const override;

 private:
  bool hand_out(const std::vector<int>& order, const std::function<std::string(int)>& compute,
                const std::function<bool(int, const std::string&)>& deliver) const;
  void work(const std::function<std::string(int)>& compute) const;
  const MpiSession& session_;
};

}  // namespace lienewton::cli
