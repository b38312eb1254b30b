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
uhpc_bad_input_case(NAME macro_leading_surface_needs_kinematic_contact
  STDERR "error: data/macro_elastic_block.json: key 'projectile.contact.surface': value 'leading' needs model 'kinematic' (the penalty's force is the gradient of its offset overlap)"
  COMMAND ${_macro} ${_macro_case} --set projectile.contact.model=penalty --set projectile.contact.surface=leading)
uhpc_bad_input_case(NAME macro_unknown_contact_surface
  STDERR "error: data/macro_elastic_block.json: key 'projectile.contact.surface': value 'front' is not one of: offset, leading"
  COMMAND ${_macro} ${_macro_case} --set projectile.contact.surface=front)
uhpc_bad_input_case(NAME macro_negative_checkpoint_clock
  STDERR "error: --checkpoint-every-min -1: not a number of minutes >= 0 (0: none)"
  COMMAND ${_macro} ${_macro_case} --checkpoint-every-min -1)
uhpc_bad_input_case(NAME macro_missing_out
  STDERR "error: --out is required"
  COMMAND ${_macro} --config data/macro_elastic_block.json)
# The size and step guards name the inputs that made their estimate absurd beside their own key (issue 48).
uhpc_bad_input_case(NAME macro_particles_beyond_the_budget
  STDERR "error: data/macro_elastic_block.json: key 'run.max_particles': the target would hold about 3.69e+10 particles (about 4.12e+05 GiB of memory) with target.size_m = [0.048, 0.048, 0.016] m, target.spacing_m = 1e-05 m, more than max_particles = 2000000 (check the target's size and spacing, or raise max_particles)"
  COMMAND ${_macro} ${_macro_case} --set target.spacing_m=1e-5)
uhpc_bad_input_case(NAME macro_steps_beyond_the_budget
  STDERR "error: data/macro_elastic_block.json: key 'run.max_steps': the run would take about 7.42e+146 steps of 8.089e-152 s to reach end_time_s = 6.000e-05 s, more than max_steps = 1000000 (raise max_steps or check the inputs: the step comes from the wave speed (material.density_kg_m3 = 2555.7, material.bulk_modulus_Pa = 1e+300, material.shear_modulus_Pa = 1.8457e+10), the spacing (target.spacing_m = 0.004 m), the sphere's speed (projectile.velocity_m_s = 100 m/s) and solver.cfl = 0.4)"
  COMMAND ${_macro} ${_macro_case} --set material.bulk_modulus_Pa=1e300)
uhpc_bad_input_case(NAME macro_step_of_zero
  STDERR "error: data/macro_elastic_block.json: key 'run.end_time_s': the first stable step is 0.000e+00 s: the run cannot advance (the step comes from the wave speed (material.density_kg_m3 = 1e-300, material.bulk_modulus_Pa = 2.20704e+10, material.shear_modulus_Pa = 1.8457e+10), the spacing (target.spacing_m = 0.004 m), the sphere's speed (projectile.velocity_m_s = 100 m/s) and solver.cfl = 0.4)"
  COMMAND ${_macro} ${_macro_case} --set material.density_kg_m3=1e-300)
# An output directory holding a directory named like a result file is bad input, not an internal error, and
# a second writer of an output directory is refused, naming the holder (issue 48).
uhpc_bad_input_case(NAME macro_directory_named_fields_h5
  STDERR "error: ${UHPC_REGRESSION_OUT}/bad_fields/fields.h5: is a directory, not a file that can be written"
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/with_directory.sh ${UHPC_REGRESSION_OUT}/bad_fields/fields.h5
          ${_macro} --config data/macro_elastic_block.json --out ${UHPC_REGRESSION_OUT}/bad_fields)
uhpc_bad_input_case(NAME macro_output_in_use
  STDERR "error: ${UHPC_REGRESSION_OUT}/bad_locked: in use by pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z: wait for it to end or write elsewhere (lock file ${UHPC_REGRESSION_OUT}/bad_locked/.uhpc.lock)"
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/hold_lock.sh ${UHPC_REGRESSION_OUT}/bad_locked/.uhpc.lock
          ${_macro} --config data/macro_elastic_block.json --out ${UHPC_REGRESSION_OUT}/bad_locked)
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
uhpc_bad_input_case(NAME compare_shots_output_in_use
  STDERR "error: ${UHPC_REGRESSION_OUT}/bad_compare_locked: in use by pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z: wait for it to end or write elsewhere (lock file ${UHPC_REGRESSION_OUT}/bad_compare_locked/.uhpc.lock)"
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/hold_lock.sh ${UHPC_REGRESSION_OUT}/bad_compare_locked/.uhpc.lock
          ${_cmp} ${_cmp_tables} --results ${_cmp_dir}/v610 --out ${UHPC_REGRESSION_OUT}/bad_compare_locked)
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

# An empty VELOCITIES reached uhpc-compare-shots as "--results --out DIR" and was reported as "--out is
# required" (issue 48): the sweep now stops before anything runs (no build, no run), exit 2, naming the variable.
add_test(NAME regression.bad_input.pipelines_sweep_empty_velocities
         COMMAND sh -c "make -C ${PROJECT_SOURCE_DIR}/pipelines --no-print-directory sweep VELOCITIES= OUT=${UHPC_REGRESSION_OUT}/bad 2>&1; echo exit=$?")
set_tests_properties(regression.bad_input.pipelines_sweep_empty_velocities PROPERTIES LABELS regression
  PASS_REGULAR_EXPRESSION "^Makefile:[0-9]+: \\*\\*\\* sweep: VELOCITIES is empty: give the impact velocities to run in m/s, e\\.g\\. VELOCITIES=\"610 817\"\\.  Stop\\.\nexit=2\n$")

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
# The band of the residual velocity over SDEL samples (make uq, issue 51): the coarse disc, 4 covariance
# samples, 2 velocities; files, provenance, the band's order, resume (about 30 s).
add_test(NAME regression.pipelines_uq_band
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_uq_band.py --source ${PROJECT_SOURCE_DIR}
                 --build ${CMAKE_BINARY_DIR} --out ${UHPC_REGRESSION_OUT}/pipelines_uq_band)
set_tests_properties(regression.pipelines_uq_band PROPERTIES LABELS regression TIMEOUT 300)
# Sobol indices through a chaos surrogate (make sensitivity, issue 51): the coarse disc, 16 design points at
# 1112 m/s; files, each run's constants, the indices' bounds, resume (about 30 s).
add_test(NAME regression.pipelines_sensitivity
         COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/check_sensitivity.py --source ${PROJECT_SOURCE_DIR}
                 --build ${CMAKE_BINARY_DIR} --out ${UHPC_REGRESSION_OUT}/pipelines_sensitivity)
set_tests_properties(regression.pipelines_sensitivity PROPERTIES LABELS regression TIMEOUT 300)
# uhpc-macro under mpirun (issue 49): a small disc's shot at 2-4 ranks against the same shot in one
# process, with lazy rows and with every row rebuilt, stopped and restarted at another rank count, with
# the full field set and the penalty contact, and with the midpoint strain configuration: the residual
# velocity, the sphere and every field bit for bit, the books to 1e-10 (about 20 s each). Open MPI's settings as in macro_tests.cmake; the
# distribution's python3 for its h5py.
if(UHPC_MPI)
  foreach(np 2 3 4)
    add_test(NAME verification.MacroMpiShot.ranks_${np}
             COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/check_mpi_shot.py --macro $<TARGET_FILE:uhpc-macro>
                     --mpirun "${UHPC_MPIEXEC} --oversubscribe -np" --ranks ${np}
                     --case ${PROJECT_SOURCE_DIR}/data/macro_disc_afc_coarse.json
                     --out ${UHPC_REGRESSION_OUT}/mpi_shot_${np})
    set_tests_properties(verification.MacroMpiShot.ranks_${np} PROPERTIES LABELS verification TIMEOUT 300
                         PROCESSORS ${np} ENVIRONMENT "${_uhpc_mpi_env}")
  endforeach()
endif()
