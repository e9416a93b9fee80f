// Independent broadband runs on oneTBB. Each run is sequential inside one task, so its numbers do
// not depend on the thread count; results are stored in job order.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include "fdtd_periodic.hpp"

namespace plumage::fdtd {

std::vector<Spectrum> run_batch(const Cell& cell, const std::vector<Job>& jobs,
                                const std::vector<double>& omegas, const SimParams& params, int threads) {
    std::vector<std::exception_ptr> errs;
    auto out = run_batch_collect(cell, jobs, omegas, params, threads, errs);
    for (auto& e : errs)
        if (e) std::rethrow_exception(e);
    return out;
}

std::vector<Spectrum> run_batch_collect(const Cell& cell, const std::vector<Job>& jobs,
                                        const std::vector<double>& omegas, const SimParams& params, int threads,
                                        std::vector<std::exception_ptr>& errs) {
    std::vector<Spectrum> out(jobs.size());
    errs.assign(jobs.size(), nullptr);
    // One job per task (runs differ several-fold in length), at most `threads` at a time.
    tbb::task_arena arena(std::max(1, threads));
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, jobs.size(), 1),
            [&](const tbb::blocked_range<std::size_t>& range) {
                for (std::size_t j = range.begin(); j != range.end(); ++j) {
                    try {
                        out[j] = run_spectrum(cell, jobs[j].kx, jobs[j].ky, omegas, params);
                    } catch (...) {
                        errs[j] = std::current_exception();
                    }
                }
            },
            tbb::simple_partitioner());
    });
    return out;
}

}  // namespace plumage::fdtd
