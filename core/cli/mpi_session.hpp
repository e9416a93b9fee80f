// Optional MPI for `plumage characterize`: active only when the process was started by an MPI
// launcher (OpenMPI's OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK or PMI_SIZE in the environment) and
// the build found MPI; otherwise a single rank and no MPI calls at all.
#pragma once

#include <string>
#include <vector>

namespace plumage::cli {

class MpiSession {
 public:
  MpiSession();  // MPI_Init if launched by mpirun
  ~MpiSession();  // MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool active() const { return active_; }
  // Every rank's bytes on rank 0 (in rank order); other ranks get an empty vector.
  std::vector<std::string> gather(const std::string& bytes) const;
  // Rank 0's flag to everyone (so all ranks agree on success before exiting).
  bool broadcast(bool flag) const;
  [[noreturn]] void abort(int code) const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace plumage::cli
