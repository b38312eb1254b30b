# Regression cases of uhpc-micro (uhpc_regression_case / uhpc_bad_input_case).
