# Regression cases of uhpc-micro (uhpc_regression_case / uhpc_bad_input_case).

# --- uhpc-micro generate / generate-ensemble on the shipped defaults ---
uhpc_regression_case(NAME micro_generate OUTPUT cell.json
  COMMAND $<TARGET_FILE:uhpc-micro> -q generate --config data/micro_cell.json)
uhpc_regression_case(NAME micro_generate_ensemble OUTPUT statistics.json
  COMMAND $<TARGET_FILE:uhpc-micro> -q generate-ensemble --config data/micro_ensemble.json --set realizations=2
          --set cell.discretization.nominal_spacing_m=1e-4)

# --- the archived cells of the shipped ensemble reload (their hash is today's) and assemble to the stored
#     ensemble_4x25.h5: a stale archive would make `make micro-ensemble` recompute all 100 cells ---
add_test(NAME regression.micro_archived_cells_reload
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/check_archived_cells.py --micro $<TARGET_FILE:uhpc-micro>
                 --source ${PROJECT_SOURCE_DIR} --out ${UHPC_REGRESSION_OUT}/micro_archived_cells)
set_tests_properties(regression.micro_archived_cells_reload PROPERTIES LABELS regression TIMEOUT 120)

# --- bad input: exit 2, one line naming file, key and reason ---
set(_micro $<TARGET_FILE:uhpc-micro>)
set(_bad ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME micro_porosity_out_of_range
  STDERR "error: data/microstructure.json: key 'area_porosity': value 0.35 is out of range, must be in (0, 0.3)"
  COMMAND ${_micro} generate --config data/micro_cell.json --set microstructure.area_porosity=0.35 --out ${_bad})
uhpc_bad_input_case(NAME micro_porosity_zero
  STDERR "error: data/microstructure.json: key 'area_porosity': value 0 is out of range, must be in (0, 0.3)"
  COMMAND ${_micro} generate --config data/micro_cell.json --set microstructure.area_porosity=0 --out ${_bad})
uhpc_bad_input_case(NAME micro_burr_nonpositive
  STDERR "error: data/microstructure.json: key 'burr.k': value -1 is out of range, must be > 0"
  COMMAND ${_micro} generate --config data/micro_cell.json --set microstructure.burr.k=-1 --out ${_bad})
uhpc_bad_input_case(NAME micro_truncation_below_gamma
  STDERR "error: data/microstructure.json: key 'burr.truncation_m': value 5e-05 must exceed gamma_m = 7.7e-05 (the smallest pore)"
  COMMAND ${_micro} generate --config data/micro_cell.json --set microstructure.burr.truncation_m=5e-5 --out ${_bad})
uhpc_bad_input_case(NAME micro_cell_too_small
  STDERR "error: data/micro_cell.json: key 'cell_size_m': cell side 0.00035 m cannot hold the smallest pore (7.7e-05 m) with two ligaments of 0.00015 m (placement.min_ligament_m)"
  COMMAND ${_micro} generate --config data/micro_cell.json --set cell_size_m=0.00035 --out ${_bad})
# Two ligaments as wide as the cell: the ligament is named, not the cell's size (issue 48).
uhpc_bad_input_case(NAME micro_ligament_wider_than_the_cell
  STDERR "error: data/micro_cell.json: key 'placement.min_ligament_m': value 1 leaves no room for a pore: two ligaments of 1 m are as wide as the cell side 0.003 m (cell_size_m) or wider"
  COMMAND ${_micro} generate --config data/micro_cell.json --set placement.min_ligament_m=1 --out ${_bad})
# A misspelt command is named, with the closest one (issue 48: "A subcommand is required" named nothing).
uhpc_bad_input_case(NAME micro_misspelt_subcommand
  STDERR "error: 'generat' is not one of uhpc-micro's commands: elastic, ensemble, generate, generate-ensemble, run (did you mean 'generate'?)"
  COMMAND ${_micro} generat --config data/micro_cell.json --out ${_bad})
# A second writer of an output directory is refused, naming the holder (issue 48).
uhpc_bad_input_case(NAME micro_output_in_use
  STDERR "error: ${_bad}/micro_locked: in use by pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z: wait for it to end or write elsewhere (lock file ${_bad}/micro_locked/.uhpc.lock)"
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/hold_lock.sh ${_bad}/micro_locked/.uhpc.lock
          ${_micro} generate --config data/micro_cell.json --out ${_bad}/micro_locked)
uhpc_bad_input_case(NAME micro_porosity_unreachable
  STDERR "error: data/microstructure.json: key 'area_porosity': porosity 0.0002 +- 1e-05 is unreachable: one smallest pore (7.7e-05 m) alone gives 0.00052"
  COMMAND ${_micro} generate --config data/micro_cell.json --set microstructure.area_porosity=0.0002
          --set porosity.tolerance=1e-5 --out ${_bad})
uhpc_bad_input_case(NAME micro_misspelt_key
  STDERR "error: data/micro_cell.json: key 'seeds.per_pores': unknown key (did you mean 'per_pore'?)"
  COMMAND ${_micro} generate --config data/micro_cell.json --set seeds.per_pores=1 --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_bad_cell_override
  STDERR "error: data/micro_cell.json: key 'discretization.nominal_spacing_m': value -1 is out of range, must be > 0"
  COMMAND ${_micro} generate-ensemble --config data/micro_ensemble.json --set cell.discretization.nominal_spacing_m=-1 --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_sizes_share_a_directory
  STDERR "error: data/micro_ensemble.json: key 'cell_sizes_m': entries 0 and 2 share the directory name size_3.0mm (sizes must differ by at least 0.1 mm)"
  COMMAND ${_micro} generate-ensemble --config data/micro_ensemble.json --set cell_sizes_m=[0.003,0.0045,0.00301] --out ${_bad})
# The guard's key and the input that made the estimate absurd (issue 48: the cell's size was not named).
uhpc_bad_input_case(NAME micro_cell_beyond_the_mesh_budget
  STDERR "error: data/micro_cell.json: key 'discretization.nominal_spacing_m': a cell of side 10 m (cell_size_m) at spacing 5e-05 m needs about 4.6e+10 mesh nodes, more than the 2e+06 a cell may have (reduce cell_size_m or raise nominal_spacing_m)"
  COMMAND ${_micro} generate --config data/micro_cell.json --set cell_size_m=10 --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_size_beyond_the_mesh_budget
  STDERR "error: data/micro_cell.json: key 'discretization.nominal_spacing_m': a cell of side 10 m (the ensemble's cell_sizes_m) at spacing 5e-05 m needs about 4.6e+10 mesh nodes, more than the 2e+06 a cell may have (reduce the ensemble's cell_sizes_m or raise nominal_spacing_m)"
  COMMAND ${_micro} generate-ensemble --config data/micro_ensemble.json --set cell_sizes_m=[0.003,10] --out ${_bad})

# --- uhpc-micro ensemble: a part of the ensemble (--only-size, --only-cell) or its assembly only ---
uhpc_bad_input_case(NAME micro_ensemble_only_size_not_in_the_ensemble
  STDERR "error: --only-size 4: not one of the ensemble's cell sizes (3, 4.5, 5, 6.5 mm)"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --only-size 4 --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_only_cell_out_of_range
  STDERR "error: --only-cell 25: out of range, the ensemble's realizations are 0 to 24"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --only-cell 25 --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_only_cell_not_a_number
  STDERR "error: Could not convert: --only-cell = first"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --only-cell first --out ${_bad})
# One writer per ensemble directory for a run over every cell, one per cell for the runs of a part (the
# batch jobs of one ensemble share its directory): a second writer is refused, naming the holder.
uhpc_bad_input_case(NAME micro_ensemble_in_use
  STDERR "error: ${_bad}/ensemble_locked: in use by pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z: wait for it to end or write elsewhere (lock file ${_bad}/ensemble_locked/.uhpc.lock)"
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/hold_lock.sh ${_bad}/ensemble_locked/.uhpc.lock
          ${_micro} ensemble --config data/micro_analysis_ensemble.json --out ${_bad}/ensemble_locked)
uhpc_bad_input_case(NAME micro_ensemble_cell_in_use
  STDERR "error: ${_bad}/cell_locked/size_3.0mm/cell_00: in use by pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z: wait for it to end or write elsewhere (lock file ${_bad}/cell_locked/size_3.0mm/cell_00/.uhpc.lock)"
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/hold_lock.sh ${_bad}/cell_locked/size_3.0mm/cell_00/.uhpc.lock
          ${_micro} ensemble --config data/micro_analysis_ensemble.json --only-size 3 --only-cell 0 --out ${_bad}/cell_locked)
uhpc_bad_input_case(NAME micro_ensemble_assemble_only_with_a_part
  STDERR "error: --only-cell excludes --assemble-only"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --assemble-only --only-cell 0 --out ${_bad})

# --- uhpc-micro elastic: RK Galerkin elastic response of the shipped cell ---
uhpc_regression_case(NAME micro_elastic OUTPUT elastic.json
  COMMAND $<TARGET_FILE:uhpc-micro> -q elastic --config data/micro_elastic.json)
uhpc_bad_input_case(NAME micro_elastic_misspelt_key
  STDERR "error: data/micro_elastic.json: key 'quadrature.triangle_point': unknown key (did you mean 'triangle_points'?)"
  COMMAND ${_micro} elastic --config data/micro_elastic.json --set quadrature.triangle_point=6 --out ${_bad})
uhpc_bad_input_case(NAME micro_elastic_no_such_rule
  STDERR "error: data/micro_elastic.json: key 'quadrature.triangle_points': value 5 is not one of: 1, 3, 6, 7, 12"
  COMMAND ${_micro} elastic --config data/micro_elastic.json --set quadrature.triangle_points=5 --out ${_bad})
uhpc_bad_input_case(NAME micro_elastic_incompressible
  STDERR "error: data/microstructure.json: key 'matrix.poissons_ratio': value 0.5 is out of range, must be in (-1, 0.5)"
  COMMAND ${_micro} elastic --config data/micro_elastic.json --set microstructure.matrix.poissons_ratio=0.5 --out ${_bad})
uhpc_bad_input_case(NAME micro_elastic_needs_mesh
  STDERR "error: data/micro_cell.json: key 'discretization.mesh': must be true: the elastic analysis integrates on the mesh"
  COMMAND ${_micro} elastic --config data/micro_elastic.json --set cell.discretization.mesh=false --out ${_bad})
uhpc_bad_input_case(NAME micro_elastic_support_too_small
  STDERR "error: data/micro_elastic.json: key 'rk.support_factor': value 0.5 is out of range, must be in [1, 4]"
  COMMAND ${_micro} elastic --config data/micro_elastic.json --set rk.support_factor=0.5 --out ${_bad})

# --- uhpc-micro ensemble --select (a resampled ensemble, docs/uncertainty.md): read before any cell ---
uhpc_bad_input_case(NAME micro_ensemble_select_out_of_range
  STDERR "error: tests/regression/micro_cell_selection/out_of_range.json: key 'sizes[0].realizations[1]': value 25 is out of range, must be in [0, 24]"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --assemble-only
          --select tests/regression/micro_cell_selection/out_of_range.json --assemble-to ${_bad}/select --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_select_size_missing
  STDERR "error: tests/regression/micro_cell_selection/size_missing.json: key 'sizes': has 3 entries, the ensemble 4 sizes (3, 4.5, 5, 6.5 mm): one entry per size, in order"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --assemble-only
          --select tests/regression/micro_cell_selection/size_missing.json --assemble-to ${_bad}/select --out ${_bad})
uhpc_bad_input_case(NAME micro_ensemble_select_without_assemble_to
  STDERR "error: --select: needs --assemble-to DIR (a resampled ensemble must not replace ${_bad}/ensemble.h5)"
  COMMAND ${_micro} ensemble --config data/micro_analysis_ensemble.json --assemble-only
          --select tests/regression/micro_cell_selection/size_missing.json --out ${_bad})
