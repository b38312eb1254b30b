#pragma once
// The porous microcell as the analysis sees it: a square [0, side] x [0, side] of matrix with circular
// pores and straight microcrack seeds rooted on the pores. Plain data, no I/O (cell_io writes it).
#include <cmath>
#include <cstdint>
#include <vector>

namespace uhpc::micro {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

// Direction of the uniaxial tension applied to the cell (docs/physics.md section 2; x by default).
enum class LoadAxis { X, Y };

struct Pore {
  Vec2 center_m;
  double diameter_m = 0.0;  // the sampled equivalent sphere diameter
  double radius_m() const { return 0.5 * diameter_m; }
  double area_m2() const { return 0.25 * M_PI * diameter_m * diameter_m; }
};

// A straight crack seed: `root_m` lies on pore `pore`'s boundary, `tip_m` in the matrix.
struct CrackSeed {
  int pore = -1;
  Vec2 root_m;
  Vec2 tip_m;
};

struct CellGeometry {
  double side_m = 0.0;
  LoadAxis load = LoadAxis::X;
  std::vector<Pore> pores;  // in placement order (largest first)
  std::vector<CrackSeed> seeds;

  double cell_area_m2() const { return side_m * side_m; }
  double pore_area_m2() const {
    double a = 0.0;
    for (const Pore& p : pores) a += p.area_m2();
    return a;
  }
  double porosity() const { return pore_area_m2() / cell_area_m2(); }  // area porosity (eq. 32)
};

}  // namespace uhpc::micro
