# Test suites of uhpc-micro (uhpc_add_test(<layer> <source> [libs...])).
uhpc_add_test(unit unit/test_micro_burr.cpp uhpc_micro)
uhpc_add_test(unit unit/test_micro_cell_generator.cpp uhpc_micro)
uhpc_add_test(unit unit/test_micro_cell_io.cpp uhpc_micro)
uhpc_add_test(verification verification/test_micro_cell_mesh.cpp uhpc_micro)
uhpc_add_test(verification verification/test_micro_elastic_patch.cpp uhpc_micro)
uhpc_add_test(verification verification/test_micro_elastic_cell.cpp uhpc_micro)
uhpc_add_test(unit unit/test_micro_quadrature.cpp uhpc_micro)
