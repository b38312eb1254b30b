# Test suites of uhpc-micro (uhpc_add_test(<layer> <source> [libs...])).
