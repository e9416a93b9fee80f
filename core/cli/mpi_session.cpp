#include "mpi_session.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef PLUMAGE_HAVE_MPI
#include <mpi.h>
#endif

namespace plumage::cli {

namespace {
bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}
}  // namespace

MpiSession::MpiSession() {
#ifdef PLUMAGE_HAVE_MPI
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  active_ = true;
#else
  if (launched_by_mpi())
    throw std::runtime_error("this plumage was built without MPI (libopenmpi-dev missing at configure time)");
#endif
}

MpiSession::~MpiSession() {
#ifdef PLUMAGE_HAVE_MPI
  if (active_) MPI_Finalize();
#endif
}

std::vector<std::string> MpiSession::gather(const std::string& bytes) const {
  if (!active_) return {bytes};
#ifdef PLUMAGE_HAVE_MPI
  long long n = static_cast<long long>(bytes.size());
  std::vector<long long> sizes(rank_ == 0 ? size_ : 0);
  MPI_Gather(&n, 1, MPI_LONG_LONG, sizes.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  if (rank_ == 0) {
    out.resize(size_);
    out[0] = bytes;
    for (int r = 1; r < size_; ++r) {
      out[r].resize(static_cast<std::size_t>(sizes[r]));
      // Point-to-point in chunks (counts are int): any size works.
      std::size_t done = 0;
      while (done < out[r].size()) {
        const int chunk = static_cast<int>(std::min<std::size_t>(out[r].size() - done, 1 << 30));
        MPI_Recv(out[r].data() + done, chunk, MPI_BYTE, r, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        done += static_cast<std::size_t>(chunk);
      }
    }
  } else {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const int chunk = static_cast<int>(std::min<std::size_t>(bytes.size() - done, 1 << 30));
      MPI_Send(bytes.data() + done, chunk, MPI_BYTE, 0, 7, MPI_COMM_WORLD);
      done += static_cast<std::size_t>(chunk);
    }
  }
  return out;
#else
  return {bytes};
#endif
}

bool MpiSession::broadcast(bool flag) const {
#ifdef PLUMAGE_HAVE_MPI
  if (active_) {
    int v = flag ? 1 : 0;
    MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v != 0;
  }
#endif
  return flag;
}

void MpiSession::abort(int code) const {
#ifdef PLUMAGE_HAVE_MPI
  if (active_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace plumage::cli
