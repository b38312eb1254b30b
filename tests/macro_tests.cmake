# Test suites of uhpc-macro (uhpc_add_test(<layer> <source> [libs...])).
uhpc_add_test(unit unit/test_macro_materials.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_bodies.cpp uhpc_macro_bodies)
