# Regression cases of uhpc-calibrate (uhpc_regression_case / uhpc_bad_input_case).
