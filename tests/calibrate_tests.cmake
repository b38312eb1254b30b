# Test suites of uhpc-calibrate (uhpc_add_test(<layer> <source> [libs...])).
uhpc_add_test(unit unit/test_calibrate_ensemble_file.cpp uhpc_calibration)
uhpc_add_test(unit unit/test_calibrate_sdel_fit.cpp uhpc_calibration)
uhpc_add_test(unit unit/test_calibrate_size_effect.cpp uhpc_calibration)
uhpc_add_test(verification verification/test_calibrate_recovery.cpp uhpc_calibration)
