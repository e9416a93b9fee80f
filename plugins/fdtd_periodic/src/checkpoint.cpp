// Resumable k-grid runs (build_steps.hpp). Records: u32 node, then per frequency u8 valid, u8
// flags (bit 0 other_orders, bits 1–2 run flags), 4 f64 angles, 12 complex (E[2], H[2]) as f64
// pairs.
#include <sstream>

#include "build_steps.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"

namespace plumage::fdtd_table::detail {

namespace {

using fdtd::Vec3c;

void write_record(std::ostream& os, std::uint32_t node, const fdtd::Spectrum& s, unsigned run_flags) {
  os.write(reinterpret_cast<const char*>(&node), 4);
  for (const auto& f : s.freqs) {
    const char flags[2] = {static_cast<char>(f.valid), static_cast<char>((f.other_orders ? 1u : 0u) | run_flags)};
    os.write(flags, 2);
    const double a[4] = {f.sin_theta, f.cos_theta, f.sin_phi, f.cos_phi};
    os.write(reinterpret_cast<const char*>(a), sizeof a);
    for (int q = 0; q < 2; ++q) {
      os.write(reinterpret_cast<const char*>(f.E[q].data()), sizeof(Vec3c));
      os.write(reinterpret_cast<const char*>(f.H[q].data()), sizeof(Vec3c));
    }
  }
}

bool read_record(std::istream& is, std::size_t nfreq, std::uint32_t& node, fdtd::Spectrum& s, unsigned& run_flags) {
  if (!is.read(reinterpret_cast<char*>(&node), 4)) return false;
  s.freqs.assign(nfreq, {});
  run_flags = 0;
  for (auto& f : s.freqs) {
    char flags[2];
    double a[4];
    if (!is.read(flags, 2) || !is.read(reinterpret_cast<char*>(a), sizeof a)) return false;
    f.valid = flags[0] != 0;
    f.other_orders = (static_cast<unsigned char>(flags[1]) & 1u) != 0;
    run_flags |= static_cast<unsigned char>(flags[1]) & (kRunNotConverged | kRunRerun);
    f.sin_theta = a[0], f.cos_theta = a[1], f.sin_phi = a[2], f.cos_phi = a[3];
    for (int q = 0; q < 2; ++q) {
      if (!is.read(reinterpret_cast<char*>(f.E[q].data()), sizeof(Vec3c))) return false;
      if (!is.read(reinterpret_cast<char*>(f.H[q].data()), sizeof(Vec3c))) return false;
    }
  }
  s.stats.converged = (run_flags & kRunNotConverged) == 0;
  return true;
}

// Everything the runs' numbers depend on (runs of another cell, grid or numerics are not reused).
std::string header_of(const Options& opt, double ax_um, const fdtd::SimParams& sim, double dk,
                      const std::vector<double>& omegas, const std::vector<fdtd::Job>& jobs) {
  std::ostringstream key;
  key.precision(17);
  key << "plumage-fdtd-checkpoint-1;" << opt.checkpoint_tag << ";ax=" << ax_um << ";nx=" << opt.nx << ";dk=" << dk
      << ";kzmin=" << sim.kz_min << ";tol=" << sim.dft_tol << ";pml=" << sim.pml_cells << ";w=";
  for (double w : omegas) key << w << ",";
  key << ";nodes=" << jobs.size() << ";";
  for (const auto& jb : jobs) key << jb.kx << "," << jb.ky << ";";
  return fnv1a_hex(key.str());
}

}  // namespace

Checkpoint::Checkpoint(const Options& opt, double ax_um, const fdtd::SimParams& sim, double k_step,
                       const std::vector<double>& omegas, const std::vector<fdtd::Job>& jobs,
                       std::vector<fdtd::Spectrum>& spectra, std::vector<char>& have, std::vector<unsigned>& run_flags) {
  if (opt.checkpoint.empty()) return;
  check_output_path(opt.checkpoint);  // rewritten below; reading a FIFO would hang
  const std::string header = header_of(opt, ax_um, sim, k_step, omegas, jobs);
  {
    std::ifstream in(opt.checkpoint, std::ios::binary);
    std::string h(16, '\0');
    if (in && in.read(h.data(), 16) && h == header) {
      std::uint32_t node;
      fdtd::Spectrum sp;
      unsigned flags = 0;
      while (read_record(in, omegas.size(), node, sp, flags)) {
        if (node < jobs.size() && !have[node]) {
          spectra[node] = std::move(sp);
          have[node] = 1;
          run_flags[node] = flags;
          ++resumed_;
        }
      }
    }
  }
  // Rewrite the file with the records read (drops a truncated tail), then append.
  file_.open(opt.checkpoint, std::ios::binary | std::ios::trunc);
  if (!file_) throw Error("fdtd_periodic: cannot write checkpoint " + opt.checkpoint);
  file_.write(header.data(), 16);
  for (std::size_t n = 0; n < jobs.size(); ++n)
    if (have[n]) write_record(file_, static_cast<std::uint32_t>(n), spectra[n], run_flags[n]);
  file_.flush();
}

void Checkpoint::append(std::uint32_t node, const fdtd::Spectrum& s, unsigned run_flags) {
  if (file_.is_open()) write_record(file_, node, s, run_flags);
}

void Checkpoint::flush() {
  if (file_.is_open()) file_.flush();
}

}  // namespace plumage::fdtd_table::detail
