# Regression cases of uhpc-macro (uhpc_regression_case / uhpc_bad_input_case).

# --- the shipped small case end to end: rigid sphere into an elastic block ---
uhpc_regression_case(NAME macro_elastic_block OUTPUT result.json
  COMMAND $<TARGET_FILE:uhpc-macro> -q --config data/macro_elastic_block.json)

# --- bad input: exit 2, one line naming file, key and reason ---
set(_macro $<TARGET_FILE:uhpc-macro>)
set(_macro_case --config data/macro_elastic_block.json --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME macro_misspelt_key
  STDERR "error: data/macro_elastic_block.json: key 'projectile.velocty_m_s': unknown key (did you mean 'velocity_m_s'?)"
  COMMAND ${_macro} ${_macro_case} --set projectile.velocty_m_s=800)
uhpc_bad_input_case(NAME macro_negative_mass
  STDERR "error: data/macro_elastic_block.json: key 'projectile.mass_kg': value -1 is out of range, must be > 0"
  COMMAND ${_macro} ${_macro_case} --set projectile.mass_kg=-1)
uhpc_bad_input_case(NAME macro_unknown_material
  STDERR "error: data/macro_elastic_block.json: key 'material.model': value 'foo' is not one of: elastic, j2, afc"
  COMMAND ${_macro} ${_macro_case} --set material.model=foo)
uhpc_bad_input_case(NAME macro_j2_needs_yield_stress
  STDERR "error: data/macro_elastic_block.json: key 'material.yield_stress_Pa': required key is missing"
  COMMAND ${_macro} ${_macro_case} --set material.model=j2)
uhpc_bad_input_case(NAME macro_bad_sdel_handoff
  STDERR "error: tests/regression/sdel_paper/bad_format.json: key 'format': expected \"uhpc-sdel/1\", got \"uhpc-sdel/0\""
  COMMAND ${_macro} ${_macro_case} --sdel tests/regression/sdel_paper/bad_format.json)
uhpc_bad_input_case(NAME macro_unknown_rim_support
  STDERR "error: data/macro_elastic_block.json: key 'support.rim': value 'clamped' is not one of: free, fixed, frame"
  COMMAND ${_macro} ${_macro_case} --set support.rim=clamped)
uhpc_bad_input_case(NAME macro_unknown_strain_configuration
  STDERR "error: data/macro_elastic_block.json: key 'solver.strain_configuration': value 'mid' is not one of: midpoint, end, endpoint_average"
  COMMAND ${_macro} ${_macro_case} --set solver.strain_configuration=mid)
uhpc_bad_input_case(NAME macro_sphere_larger_than_target
  STDERR "error: data/macro_elastic_block.json: key 'projectile.radius_m': the sphere must be smaller than the target's half width"
  COMMAND ${_macro} ${_macro_case} --set projectile.radius_m=0.03)
uhpc_bad_input_case(NAME macro_disc_without_radius
  STDERR "error: data/macro_elastic_block.json: key 'target.radius_m': required key is missing"
  COMMAND ${_macro} ${_macro_case} --set target.shape=disc)
uhpc_bad_input_case(NAME macro_zero_output_interval
  STDERR "error: data/macro_elastic_block.json: key 'run.output_interval_steps': value 0 is out of range, must be >= 1"
  COMMAND ${_macro} ${_macro_case} --set run.output_interval_steps=0)
uhpc_bad_input_case(NAME macro_missing_out
  STDERR "error: --out is required"
  COMMAND ${_macro} --config data/macro_elastic_block.json)
uhpc_bad_input_case(NAME macro_afc_needs_constants_file
  STDERR "error: data/macro_elastic_block.json: key 'material.constants_file': required key is missing"
  COMMAND ${_macro} ${_macro_case} --set material.model=afc)

# --- uhpc-compare-shots (issue 7) on hand-written result.json files (not runs) ---
set(_cmp $<TARGET_FILE:uhpc-compare-shots>)
set(_cmp_tables --experiments data/table5_ballistic_experiments.csv --paper data/table8_paper_simulations.csv
                --projectile data/projectile.json)
set(_cmp_dir tests/regression/compare_shots)
uhpc_regression_case(NAME compare_shots OUTPUT comparison.json
  COMMAND ${_cmp} ${_cmp_tables} --results ${_cmp_dir}/v1112 ${_cmp_dir}/v610 ${_cmp_dir}/v903 ${_cmp_dir}/v689/
          ${_cmp_dir}/v992/result.json ${_cmp_dir}/v613 ${_cmp_dir}/v817)
set(_cmp_spread tests/regression/compare_shots_spread)
uhpc_regression_case(NAME compare_shots_spread OUTPUT spread.json
  COMMAND ${_cmp} --spread --reference graded --results ${_cmp_spread}/uniform_3.0mm ${_cmp_spread}/graded
          ${_cmp_spread}/uniform_4.5mm)
set(_cmp_six ${_cmp_dir}/v610 ${_cmp_dir}/v613 ${_cmp_dir}/v689 ${_cmp_dir}/v817 ${_cmp_dir}/v903 ${_cmp_dir}/v992)
uhpc_bad_input_case(NAME compare_shots_missing_shot
  STDERR "error: data/table5_ballistic_experiments.csv: row 7 (impact velocity 1112 m/s) has no shot among the 6 result(s) given (within 1 m/s)"
  COMMAND ${_cmp} ${_cmp_tables} --require-experiments --results ${_cmp_six} --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_unmatched_velocity
  STDERR "error: tests/regression/compare_shots_bad/v700/result.json: impact velocity 700 m/s matches no experiment of data/table5_ballistic_experiments.csv (within 1 m/s)"
  COMMAND ${_cmp} ${_cmp_tables} --require-experiments --results ${_cmp_six} tests/regression/compare_shots_bad/v700 --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_twice_the_same_shot
  STDERR "error: tests/regression/compare_shots/v610/result.json: impact velocity 610 m/s pairs with the 610 m/s experiment that tests/regression/compare_shots/v610/result.json already pairs with"
  COMMAND ${_cmp} ${_cmp_tables} --results ${_cmp_six} ${_cmp_dir}/v610 --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_failed_run
  STDERR "error: tests/regression/compare_shots_bad/failed/result.json: missing: the run failed (see tests/regression/compare_shots_bad/failed/diagnostic.json)"
  COMMAND ${_cmp} ${_cmp_tables} --results ${_cmp_six} tests/regression/compare_shots_bad/failed --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_missing_run
  STDERR "error: tests/regression/compare_shots_bad/nothere/result.json: cannot open file (No such file or directory)"
  COMMAND ${_cmp} ${_cmp_tables} --results tests/regression/compare_shots_bad/nothere --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_result_without_energy_balance
  STDERR "error: tests/regression/compare_shots_bad/no_energy_balance/result.json: key 'energy.balance_error': required key is missing"
  COMMAND ${_cmp} ${_cmp_tables} --results tests/regression/compare_shots_bad/no_energy_balance --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_spread_mixed_shots
  STDERR "error: tests/regression/compare_shots/v610/result.json: impact velocity 610 m/s differs from the reference run's 817 m/s (tests/regression/compare_shots_spread/graded/result.json): a spread compares runs of one shot"
  COMMAND ${_cmp} --spread --results ${_cmp_spread}/graded ${_cmp_dir}/v610 --out ${UHPC_REGRESSION_OUT}/bad)
uhpc_bad_input_case(NAME compare_shots_missing_out
  STDERR "error: --out is required"
  COMMAND ${_cmp} --results ${_cmp_dir}/v610)

# Without --require-experiments a shot off every experiment (700 m/s) is listed, outside the statistics,
# and an experiment without a shot (1112 m/s) is named in the notes.
uhpc_regression_case(NAME compare_shots_unmatched OUTPUT comparison.json
  COMMAND ${_cmp} ${_cmp_tables} --results ${_cmp_six} tests/regression/compare_shots_bad/v700)

# The sweep, thickness-study and report targets of pipelines/Makefile on the coarse disc (5 short runs,
# about half a minute): tables equal to the runs' result.json, the fit inside its bootstrap interval,
# resumable, the thickness study reusing the sweep's runs, the report's figures and provenance.
add_test(NAME regression.pipelines_sweep_thickness_report
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_sweep_pipeline.py --source ${PROJECT_SOURCE_DIR}
                 --build ${CMAKE_BINARY_DIR} --out ${UHPC_REGRESSION_OUT}/pipelines_sweep)
set_tests_properties(regression.pipelines_sweep_thickness_report PROPERTIES LABELS regression TIMEOUT 300)
