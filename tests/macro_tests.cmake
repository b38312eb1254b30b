# Test suites of uhpc-macro (uhpc_add_test(<layer> <source> [libs...])).
uhpc_add_test(unit unit/test_macro_materials.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_bodies.cpp uhpc_macro_bodies)
uhpc_add_test(verification verification/test_macro_wave_speed.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_bar_impact.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_solver_kinematics.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_conservation.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_zero_modes.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_second_gradients.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_step_allocations.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_afc.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_config.cpp uhpc_macro_materials)
uhpc_add_test(verification verification/test_macro_afc_check_values.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_allocations.cpp uhpc_macro_materials)
# Sphere contact, step-collapse guard, robustness exits and the uhpc-macro program.
uhpc_add_test(verification verification/test_macro_sphere_contact.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_robustness.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_app.cpp uhpc_macro_app)
add_dependencies(unit_test_macro_app uhpc-macro)  # the exit-code test runs the program
