#pragma once
// The enriched-RKPM cohesive-crack solver (analysis/cell_analysis.hpp) as the CellAnalyzer of the
// `run` and `ensemble` drivers: the "analysis" section gives the solver options, the cell's
// microstructure file its Table 2 matrix.
#include "cell_analyzer.hpp"

namespace uhpc::micro {

CellAnalyzerFactory fracture_analyzer_factory();

}  // namespace uhpc::micro
