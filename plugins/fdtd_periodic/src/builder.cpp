#include "builder.hpp"

namespace plumage::fdtd_table {

ReflectionTable FdtdTableBuilder::build(const CrystalCell& cell, const TableGrid& grid, Progress progress) const {
  const BuildPlan plan = plan_build(params_, cell);
  return build_table([&cell](double lambda_um) { return cell_from_crystal(cell, lambda_um); }, cell.a_x_nm * 1e-3,
                     grid, plan.meta, plan.options, progress);
}

}  // namespace plumage::fdtd_table
