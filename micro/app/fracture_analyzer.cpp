#include "fracture_analyzer.hpp"

#include "cell_analysis.hpp"
#include "cell_analysis_settings.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::micro {

CellAnalyzerFactory fracture_analyzer_factory() {
  return [](const Config& analysis, double curve_end_strain) -> CellAnalyzer {
    const CellAnalysisOptions options = read_cell_analysis_options(analysis, curve_end_strain);
    return [options](const CellJob& job, const StateObserver& observe) {
      if (!job.mesh)
        throw InputError(job.cell_config + ": key 'discretization.mesh': must be true for the crack analysis");
      const CellMaterial material = read_cell_material(Config::load(job.settings.microstructure_file).section("matrix"));
      return analyze_cell(job.cell->geometry, *job.mesh, material, options, observe);
    };
  };
}

}  // namespace uhpc::micro
