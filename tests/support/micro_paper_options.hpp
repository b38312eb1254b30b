#pragma once
// The paper's microcell options (Table 1 Burr law, 1.3 mm truncation, 3.4 % porosity, the shipped
// placement and seed defaults of data/micro_cell.json) for the micro test suites.
#include "cell_generator.hpp"

namespace uhpc::micro {

inline CellOptions paper_options(double side_m) {
  CellOptions o;
  o.side_m = side_m;
  o.burr = {3.9313, 1.1698, 290.43e-6, 77e-6};
  o.truncation_m = 1.3e-3;
  o.porosity = {0.034, 0.0005, 1000000};
  o.placement = {150e-6, 100000};
  o.seeds = {2, 50e-6, 0.0};
  return o;
}

}  // namespace uhpc::micro
