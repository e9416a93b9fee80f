// Ranks of a characterisation: this process, or the ranks of an MPI launch (mpi_distribution.hpp).
#include "mpi_distribution.hpp"

#include <algorithm>
#include <cstdlib>

#include "plumage/error.hpp"

#ifdef PLUMAGE_HAVE_MPI
#include <mpi.h>
#endif

namespace plumage {

namespace {

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}

class SingleRank final : public Ranks {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  bool active() const override { return false; }
  std::vector<std::string> gather(const std::string& bytes) const override { return {bytes}; }
  bool broadcast(bool flag) const override { return flag; }
  [[noreturn]] void abort(int code) const override { std::exit(code); }
};

#ifdef PLUMAGE_HAVE_MPI
// Counts are int: any size goes point to point in chunks of 1 GiB.
constexpr std::size_t kChunk = std::size_t{1} << 30;

class MpiRanks final : public Ranks {
 public:
  MpiRanks() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiRanks() override { MPI_Finalize(); }
  MpiRanks(const MpiRanks&) = delete;
  MpiRanks& operator=(const MpiRanks&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  bool active() const override { return true; }

  std::vector<std::string> gather(const std::string& bytes) const override {
    long long n = static_cast<long long>(bytes.size());
    std::vector<long long> sizes(rank_ == 0 ? size_ : 0);
    MPI_Gather(&n, 1, MPI_LONG_LONG, sizes.data(), 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
    std::vector<std::string> out;
    if (rank_ == 0) {
      out.resize(size_);
      out[0] = bytes;
      for (int r = 1; r < size_; ++r) {
        out[r].resize(static_cast<std::size_t>(sizes[r]));
        for (std::size_t done = 0; done < out[r].size();) {
          const int chunk = static_cast<int>(std::min(out[r].size() - done, kChunk));
          MPI_Recv(out[r].data() + done, chunk, MPI_BYTE, r, 7, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          done += static_cast<std::size_t>(chunk);
        }
      }
    } else {
      for (std::size_t done = 0; done < bytes.size();) {
        const int chunk = static_cast<int>(std::min(bytes.size() - done, kChunk));
        MPI_Send(bytes.data() + done, chunk, MPI_BYTE, 0, 7, MPI_COMM_WORLD);
        done += static_cast<std::size_t>(chunk);
      }
    }
    return out;
  }

  bool broadcast(bool flag) const override {
    int v = flag ? 1 : 0;
    MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v != 0;
  }

  [[noreturn]] void abort(int code) const override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
  }

 private:
  int rank_ = 0, size_ = 1;
};
#endif

}  // namespace

const Ranks& single_rank() {
  static const SingleRank single;
  return single;
}

const Ranks& launch_ranks() {
  if (!launched_by_mpi()) return single_rank();
#ifdef PLUMAGE_HAVE_MPI
  static const MpiRanks ranks;
  return ranks;
#else
  throw Error("this plumage was built without MPI (libopenmpi-dev missing at configure time)");
#endif
}

}  // namespace plumage
