# Regression cases of uhpc-calibrate. The program writes a file (--out sdel.json), not a directory, so
# the run / compare steps are spelt out here rather than through uhpc_regression_case; the bad-input
# cases use uhpc_bad_input_case. Inputs are made by `uhpc-calibrate synthesize` from the paper's
# handoff (data/sdel_paper.json) in fixtures; the one stored binary input is the microcell ensemble
# data/micro_analysis_ensemble_cells/ensemble_4x25.h5 (hours to compute).
set(CAL ${UHPC_REGRESSION_OUT}/calibrate)
set(CAL_EXE $<TARGET_FILE:uhpc-calibrate>)

# A step of a chain: runs COMMAND, provides fixture SETUP, needs fixtures REQUIRES.
function(uhpc_calibrate_step name)
  cmake_parse_arguments(S "" "SETUP" "REQUIRES;COMMAND" ${ARGN})
  add_test(NAME regression.${name} COMMAND ${S_COMMAND} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(regression.${name} PROPERTIES LABELS regression)
  if(S_SETUP)
    set_tests_properties(regression.${name} PROPERTIES FIXTURES_SETUP "${S_SETUP}")
  endif()
  if(S_REQUIRES)
    set_tests_properties(regression.${name} PROPERTIES FIXTURES_REQUIRED "${S_REQUIRES}")
  endif()
endfunction()

# --- the chain synthetic ensemble (1 % noise) -> calibrate -> uhpc-sdel on the fitted handoff ---
uhpc_calibrate_step(calibrate_synthetic.synthesize SETUP cal_noisy_h5
  COMMAND ${CAL_EXE} synthesize --sdel data/sdel_paper.json --noise 0.01 --seed 7 --out ${CAL}/noisy/ensemble.h5)
uhpc_calibrate_step(calibrate_synthetic.run SETUP cal_noisy_fit REQUIRES cal_noisy_h5
  COMMAND ${CAL_EXE} --ensemble ${CAL}/noisy/ensemble.h5 --out ${CAL}/noisy/sdel.json)
uhpc_calibrate_step(calibrate_synthetic.compare REQUIRES cal_noisy_fit
  COMMAND uhpc-compare-json ${CMAKE_CURRENT_SOURCE_DIR}/calibrate_synthetic/expected.json ${CAL}/noisy/sdel.json)
uhpc_calibrate_step(calibrate_synthetic.sdel SETUP cal_noisy_sdel REQUIRES cal_noisy_fit
  COMMAND $<TARGET_FILE:uhpc-sdel> --config data/sdel_curves.json --sdel ${CAL}/noisy/sdel.json --out ${CAL}/noisy/sdel)
uhpc_calibrate_step(calibrate_synthetic.sdel_compare REQUIRES cal_noisy_sdel
  COMMAND uhpc-compare-json ${CMAKE_CURRENT_SOURCE_DIR}/calibrate_synthetic/expected_sdel_summary.json
          ${CAL}/noisy/sdel/summary.json)

# --- the stored microcell ensemble (4 x 25 cells of uhpc-micro ensemble) -> calibrate ---
uhpc_calibrate_step(calibrate_microcells.run SETUP cal_micro_fit
  COMMAND ${CAL_EXE} --ensemble data/micro_analysis_ensemble_cells/ensemble_4x25.h5 --out ${CAL}/microcells/sdel.json)
uhpc_calibrate_step(calibrate_microcells.compare REQUIRES cal_micro_fit
  COMMAND uhpc-compare-json ${CMAKE_CURRENT_SOURCE_DIR}/calibrate_microcells/expected.json ${CAL}/microcells/sdel.json)

# --- noise-free: Table 4 fitted back ---
uhpc_calibrate_step(calibrate_clean.synthesize SETUP cal_clean_h5
  COMMAND ${CAL_EXE} synthesize --sdel data/sdel_paper.json --out ${CAL}/clean/ensemble.h5)
uhpc_calibrate_step(calibrate_clean.run SETUP cal_clean_fit REQUIRES cal_clean_h5
  COMMAND ${CAL_EXE} --ensemble ${CAL}/clean/ensemble.h5 --out ${CAL}/clean/sdel.json --report ${CAL}/clean/report)
uhpc_calibrate_step(calibrate_clean.compare REQUIRES cal_clean_fit
  COMMAND uhpc-compare-json ${CMAKE_CURRENT_SOURCE_DIR}/calibrate_clean/expected.json ${CAL}/clean/report/fit_report.json)

# --- bad input: one line, exit code 2 ---
add_executable(calibrate-corrupt-ensemble ${CMAKE_CURRENT_SOURCE_DIR}/calibrate_bad_inputs/corrupt_ensemble.cpp)
target_link_libraries(calibrate-corrupt-ensemble PRIVATE uhpc::common uhpc_warnings)
set(BAD ${CAL}/bad)
uhpc_calibrate_step(calibrate_bad.synthesize SETUP cal_bad_valid
  COMMAND ${CAL_EXE} synthesize --sdel data/sdel_paper.json --out ${BAD}/valid.h5)
uhpc_calibrate_step(calibrate_bad.single_size SETUP cal_bad_files
  COMMAND ${CAL_EXE} synthesize --sdel data/sdel_paper.json --set sizes_m=[0.003] --out ${BAD}/single_size.h5)
uhpc_calibrate_step(calibrate_bad.no_softening SETUP cal_bad_files
  COMMAND ${CAL_EXE} synthesize --sdel data/sdel_paper.json --set strain_max=2e-4 --out ${BAD}/no_softening.h5)
uhpc_calibrate_step(calibrate_bad.drop_std SETUP cal_bad_files REQUIRES cal_bad_valid
  COMMAND calibrate-corrupt-ensemble ${BAD}/valid.h5 ${BAD}/no_std.h5 drop /damage/std)
uhpc_calibrate_step(calibrate_bad.nan SETUP cal_bad_files REQUIRES cal_bad_valid
  COMMAND calibrate-corrupt-ensemble ${BAD}/valid.h5 ${BAD}/nan.h5 nan /damage/mean 1 17)

function(uhpc_calibrate_bad_case name stderr)
  uhpc_bad_input_case(NAME ${name} STDERR "${stderr}" COMMAND ${ARGN})
  set_tests_properties(regression.bad_input.${name} PROPERTIES FIXTURES_REQUIRED cal_bad_files)
endfunction()

uhpc_calibrate_bad_case(calibrate_missing_file
  "error: tests/regression/calibrate_bad_inputs/missing.h5: cannot open file (No such file or directory)"
  ${CAL_EXE} --ensemble tests/regression/calibrate_bad_inputs/missing.h5 --out ${BAD}/out/sdel.json)
uhpc_calibrate_bad_case(calibrate_missing_dataset
  "error: ${BAD}/no_std.h5: dataset '/damage/std': required dataset is missing"
  ${CAL_EXE} --ensemble ${BAD}/no_std.h5 --out ${BAD}/out/sdel.json)
uhpc_calibrate_bad_case(calibrate_nan
  "error: ${BAD}/nan.h5: dataset '/damage/mean': NaN value at size index 1 (0.0045 m), strain index 17"
  ${CAL_EXE} --ensemble ${BAD}/nan.h5 --out ${BAD}/out/sdel.json)
uhpc_calibrate_bad_case(calibrate_single_size
  "error: ${BAD}/single_size.h5: dataset '/sizes': only one size (0.003 m), but a and A cannot both be fitted from one size, where e_i = A / sqrt(1 + a lambda) is a single number: the fit needs at least 2 sizes"
  ${CAL_EXE} --ensemble ${BAD}/single_size.h5 --out ${BAD}/out/sdel.json)
uhpc_calibrate_bad_case(calibrate_no_softening
  "error: ${BAD}/no_softening.h5: dataset '/damage/mean': size index 0 (lambda 0.00738189): the mean damage curve does not rise through 0.1, 0.5 and 0.9 on the strain grid, so the softening the SDEL describes is not in the data"
  ${CAL_EXE} --ensemble ${BAD}/no_softening.h5 --out ${BAD}/out/sdel.json)
uhpc_calibrate_bad_case(calibrate_misspelt_override
  "error: ${CMAKE_SOURCE_DIR}/data/calibrate.json: key 'weigthing': unknown key (did you mean 'weighting'?)"
  ${CAL_EXE} --ensemble ${BAD}/valid.h5 --set weigthing=spread --out ${BAD}/out/sdel.json)
# An unusable --out is bad input found before the fit (issue 48: exit 1 "internal error" after the fit).
uhpc_calibrate_bad_case(calibrate_out_is_a_directory
  "error: tests/regression/calibrate_bad_inputs: is a directory, not a file that can be written"
  ${CAL_EXE} --ensemble ${BAD}/valid.h5 --out tests/regression/calibrate_bad_inputs)
uhpc_calibrate_bad_case(calibrate_synthesize_out_is_a_directory
  "error: tests/regression/calibrate_bad_inputs: is a directory, not a file that can be written"
  ${CAL_EXE} synthesize --sdel data/sdel_paper.json --out tests/regression/calibrate_bad_inputs)
uhpc_calibrate_bad_case(calibrate_synthesize_out_under_proc
  "error: /proc/uhpc/ensemble.h5: cannot create the directory '/proc/uhpc': No such file or directory"
  ${CAL_EXE} synthesize --sdel data/sdel_paper.json --out /proc/uhpc/ensemble.h5)
uhpc_calibrate_bad_case(calibrate_synthesize_out_in_proc
  "error: /proc/ensemble.h5: cannot create the lock file '/proc/.ensemble.h5.lock': No such file or directory"
  ${CAL_EXE} synthesize --sdel data/sdel_paper.json --out /proc/ensemble.h5)
# A second writer of the same --out is refused, naming the holder (issue 48).
uhpc_calibrate_bad_case(calibrate_output_in_use
  "error: ${BAD}/locked/sdel.json: in use by pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z: wait for it to end or write elsewhere (lock file ${BAD}/locked/.sdel.json.lock)"
  ${CMAKE_CURRENT_SOURCE_DIR}/hold_lock.sh ${BAD}/locked/.sdel.json.lock
  ${CAL_EXE} --ensemble ${BAD}/valid.h5 --out ${BAD}/locked/sdel.json)
uhpc_calibrate_bad_case(calibrate_missing_ensemble_option
  "error: --ensemble is required"
  ${CAL_EXE} --out ${BAD}/out/sdel.json)

# A fit no start can finish (spread weights of 1 / 1e-300 overflow every residual to infinity) is a
# numerical failure: exit 1, one line naming the ensemble, and fit_diagnostic.json with every start.
set(FAIL_DIR ${BAD}/fit_failure)
add_test(NAME regression.calibrate_fit_failure
         COMMAND ${CMAKE_COMMAND}
                 "-DCOMMAND=${CAL_EXE}|--ensemble|${BAD}/valid.h5|--out|${FAIL_DIR}/sdel.json|--set|weighting=spread|--set|damage_resolution=1e-300"
                 -DEXPECTED_CODE=1
                 "-DEXPECTED_STDERR=numerical failure: ${BAD}/valid.h5: no start of the SDEL fit reached a finite optimum (8 starts; each start's end and the solver's message in ${FAIL_DIR}/fit_diagnostic.json)"
                 -DEXPECTED_FILE=${FAIL_DIR}/fit_diagnostic.json "-DEXPECTED_FILE_TEXT=\"origin\": \"data-driven linear solve\""
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/expect_failure.cmake
         WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
set_tests_properties(regression.calibrate_fit_failure PROPERTIES LABELS regression FIXTURES_REQUIRED cal_bad_valid)

# --- the SDEL's uncertainty (pipelines/uq_sdel.py, issue 51): 4 realizations of each size of the archived
#     cells, 3 bootstrap and 3 covariance samples; files, provenance, the assembly with multiplicities,
#     the summary, resume and refusal (about 20 s) ---
add_test(NAME regression.uq_sdel_tiny
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/check_uq_sdel.py --micro $<TARGET_FILE:uhpc-micro>
                 --calibrate $<TARGET_FILE:uhpc-calibrate> --sdel-program $<TARGET_FILE:uhpc-sdel>
                 --source ${PROJECT_SOURCE_DIR} --out ${UHPC_REGRESSION_OUT}/uq_sdel_tiny)
set_tests_properties(regression.uq_sdel_tiny PROPERTIES LABELS regression TIMEOUT 180)
