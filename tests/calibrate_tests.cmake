# Test suites of uhpc-calibrate (uhpc_add_test(<layer> <source> [libs...])).
