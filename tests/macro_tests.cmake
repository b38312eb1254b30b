# Test suites of uhpc-macro (uhpc_add_test(<layer> <source> [libs...])).
uhpc_add_test(unit unit/test_macro_materials.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_bodies.cpp uhpc_macro_bodies)
uhpc_add_test(verification verification/test_macro_wave_speed.cpp uhpc_macro_solver)
# The energy per crack area of a bar pulled apart, against the spacing (sdel_regularization).
uhpc_add_test(verification verification/test_macro_crack_band.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_bar_impact.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_taylor_bar.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_solver_kinematics.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_conservation.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_zero_modes.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_second_gradients.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_step_allocations.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_afc.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_config.cpp uhpc_macro_materials)
uhpc_add_test(verification verification/test_macro_afc_check_values.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_allocations.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_tension.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_failed.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_lode_limit.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_tensile_rate.cpp uhpc_macro_materials)
uhpc_add_test(unit unit/test_macro_afc_crack_band.cpp uhpc_macro_materials)
# The tensile DIF in a one-dimensional spall (plate impact in uniaxial strain) in the explicit solver.
uhpc_add_test(verification verification/test_macro_spall.cpp uhpc_macro_solver)
# Sphere contact, step-collapse guard, robustness exits and the uhpc-macro program.
uhpc_add_test(verification verification/test_macro_sphere_contact.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_contact_convergence.cpp uhpc_macro_solver)
uhpc_add_test(verification verification/test_macro_contact_swept_mass.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_robustness.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_app.cpp uhpc_macro_app)
add_dependencies(unit_test_macro_app uhpc-macro)  # the exit-code test runs the program
uhpc_add_test(verification verification/test_macro_nsni_surface_load.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_fused_shapes.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_nsni_return.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_neighbour_skin.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_lazy_rows.cpp uhpc_macro_solver)
uhpc_add_test(unit unit/test_macro_verlet_candidates.cpp uhpc_macro_solver)
# uhpc-compare-shots (issue 7): the comparison with Tables 5 and 8 and the spread of one shot.
uhpc_add_test(unit unit/test_macro_shot_comparison.cpp uhpc_macro_shots)
uhpc_add_test(unit unit/test_macro_checkpoint.cpp uhpc_macro_app uhpc_hdf5)  # (hdf5: a file without checksums)
uhpc_add_test(unit unit/test_macro_run_warnings.cpp uhpc_macro_app)
uhpc_add_test(unit unit/test_macro_panel_damage.cpp uhpc_macro_app)
uhpc_add_test(unit unit/test_macro_impact_outcome.cpp uhpc_macro_app)
add_dependencies(unit_test_macro_checkpoint uhpc-macro)  # the restart test runs the program

# The distributed layer under mpirun at 1-4 ranks (oversubscribed on small machines) and as a program
# started without mpirun (one rank). Open MPI refuses root unless told; CI runs as root, so the tests
# say so themselves, as Open MPI documents; the machine is not configured for it.
if(UHPC_MPI)
  add_executable(unit_test_macro_distributed unit/test_macro_distributed.cpp support/mpi_test_main.cpp)
  target_link_libraries(unit_test_macro_distributed PRIVATE uhpc_macro_distributed GTest::gtest uhpc_warnings)
  set(_uhpc_mpi_env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1"
                    "OMPI_MCA_btl_vader_single_copy_mechanism=none")
  if(UHPC_SANITIZE)
    # Open MPI leaves its start-up allocations to the process's end: LeakSanitizer would fail every
    # rank. AddressSanitizer and UBSan still check the code.
    list(APPEND _uhpc_mpi_env "ASAN_OPTIONS=detect_leaks=0")
  endif()
  set(_uhpc_mpirun ${UHPC_MPIEXEC} --oversubscribe -np)
  # The cases PREFIX.ranks_N: TARGET under mpirun at each rank count N given after the timeout.
  function(uhpc_add_mpi_tests prefix target label timeout)
    foreach(np ${ARGN})
      add_test(NAME ${prefix}.ranks_${np} COMMAND ${_uhpc_mpirun} ${np} $<TARGET_FILE:${target}>)
      set_tests_properties(${prefix}.ranks_${np} PROPERTIES LABELS ${label} TIMEOUT ${timeout} PROCESSORS ${np}
                           ENVIRONMENT "${_uhpc_mpi_env}")
    endforeach()
  endfunction()
  uhpc_add_mpi_tests(unit.MacroDistributed unit_test_macro_distributed unit 180 1 2 3 4)
  uhpc_add_test(unit unit/test_macro_huge_pages.cpp uhpc_macro_distributed)
  add_test(NAME unit.MacroDistributed.without_mpirun COMMAND unit_test_macro_distributed)
  set_tests_properties(unit.MacroDistributed.without_mpirun PROPERTIES LABELS unit TIMEOUT 180
                       ENVIRONMENT "${_uhpc_mpi_env}")
  # A solver's particles as records: partitioned and gathered back bit for bit, at 1-3 ranks.
  add_executable(unit_test_macro_distributed_records unit/test_macro_distributed_records.cpp support/mpi_test_main.cpp)
  target_link_libraries(unit_test_macro_distributed_records PRIVATE uhpc_macro_distributed uhpc_macro_app
                        GTest::gtest uhpc_warnings)
  target_compile_definitions(unit_test_macro_distributed_records PRIVATE UHPC_DATA_DIR="${CMAKE_SOURCE_DIR}/data")
  target_include_directories(unit_test_macro_distributed_records PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/support)
  uhpc_add_mpi_tests(unit.MacroDistributedRecords unit_test_macro_distributed_records unit 300 1 2 3)
  # The halo's depth on the real rows and internal force: the serial force bit for bit at 1-4 ranks.
  add_executable(verification_test_macro_distributed_rows verification/test_macro_distributed_rows.cpp
                 support/mpi_test_main.cpp)
  target_link_libraries(verification_test_macro_distributed_rows PRIVATE uhpc_macro_distributed uhpc_macro_solver
                        GTest::gtest uhpc_warnings)
  uhpc_add_mpi_tests(verification.MacroDistributedRows verification_test_macro_distributed_rows verification 300 1 2 3 4)
  # The distributed step: a struck disc stepped at 1-4 ranks equals the one-process run bit for bit.
  add_executable(verification_test_macro_distributed_step verification/test_macro_distributed_step.cpp
                 support/mpi_test_main.cpp)
  target_link_libraries(verification_test_macro_distributed_step PRIVATE uhpc_macro_distributed uhpc_macro_app
                        GTest::gtest uhpc_warnings)
  target_compile_definitions(verification_test_macro_distributed_step PRIVATE UHPC_DATA_DIR="${CMAKE_SOURCE_DIR}/data")
  uhpc_add_mpi_tests(verification.MacroDistributedStep verification_test_macro_distributed_step verification 600 1 2 3 4)
endif()
