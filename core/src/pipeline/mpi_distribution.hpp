// Private to the pipeline: the ranks a characterisation runs on (mpi_distribution.cpp). MPI is
// optional (PLUMAGE_HAVE_MPI, set when the build found it) and used only when the process was
// started by an MPI launcher (OpenMPI's OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK or PMI_SIZE in
// the environment); otherwise a single rank and no MPI calls at all.
#pragma once

#include <string>
#include <vector>

namespace plumage {

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  virtual bool active() const = 0;  // an MPI launch
  // Every rank's bytes on rank 0 (in rank order); other ranks get an empty vector.
  virtual std::vector<std::string> gather(const std::string& bytes) const = 0;
  // Rank 0's flag to everyone (so all ranks agree on success before exiting).
  virtual bool broadcast(bool flag) const = 0;
  // Ends every rank of the launch (MPI_Abort) or, for a single process, this one.
  [[noreturn]] virtual void abort(int code) const = 0;
};

// This process alone.
const Ranks& single_rank();
// The ranks of the MPI launch this process belongs to (MPI initialised on first use, finalised
// at exit), or single_rank() when not launched by MPI. Throws Error when launched by MPI but
// built without it.
const Ranks& launch_ranks();

}  // namespace plumage
