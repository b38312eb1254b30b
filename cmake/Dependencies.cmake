# Every third-party package the project uses, found once here. A missing one stops the configure step
# with a message naming the package and the installer that provides it.

set(UHPC_INSTALLER "pipelines/install-deps.sh")

macro(uhpc_missing what debian_package)
  message(FATAL_ERROR
    "Missing dependency: ${what} (Debian package ${debian_package}).\n"
    "Install every dependency with: bash ${UHPC_INSTALLER}")
endmacro()

macro(uhpc_find_config name debian_package)
  find_package(${name} ${ARGN} CONFIG QUIET)
  if(NOT ${name}_FOUND)
    uhpc_missing(${name} ${debian_package})
  endif()
endmacro()

uhpc_find_config(Eigen3 libeigen3-dev)
uhpc_find_config(nlohmann_json nlohmann-json3-dev)
uhpc_find_config(CLI11 libcli11-dev)
uhpc_find_config(fmt libfmt-dev)
uhpc_find_config(spdlog libspdlog-dev)
uhpc_find_config(Ceres libceres-dev)
uhpc_find_config(CGAL libcgal-dev)

find_package(HDF5 QUIET COMPONENTS C)
if(NOT HDF5_FOUND)
  uhpc_missing(HDF5 libhdf5-dev)
endif()
add_library(uhpc_hdf5 INTERFACE)
target_include_directories(uhpc_hdf5 SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS} ${HDF5_INCLUDE_DIRS})
target_link_libraries(uhpc_hdf5 INTERFACE ${HDF5_C_LIBRARIES} ${HDF5_LIBRARIES})
target_compile_definitions(uhpc_hdf5 INTERFACE ${HDF5_C_DEFINITIONS} ${HDF5_DEFINITIONS})

# SuiteSparse 5.x ships neither CMake configs nor pkg-config files on Debian 12.
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
set(_uhpc_ss_libs)
foreach(lib cholmod umfpack spqr amd colamd camd ccolamd suitesparseconfig)
  find_library(SUITESPARSE_${lib}_LIBRARY ${lib})
  if(NOT SUITESPARSE_${lib}_LIBRARY)
    uhpc_missing("SuiteSparse (lib${lib})" libsuitesparse-dev)
  endif()
  list(APPEND _uhpc_ss_libs ${SUITESPARSE_${lib}_LIBRARY})
endforeach()
if(NOT SUITESPARSE_INCLUDE_DIR)
  uhpc_missing("SuiteSparse (cholmod.h)" libsuitesparse-dev)
endif()
add_library(uhpc_suitesparse INTERFACE)
target_include_directories(uhpc_suitesparse SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(uhpc_suitesparse INTERFACE ${_uhpc_ss_libs})

# gmsh: the C++ API header and library (no CMake config), plus the command-line mesher.
find_path(GMSH_INCLUDE_DIR gmsh.h)
find_library(GMSH_LIBRARY gmsh)
if(NOT GMSH_INCLUDE_DIR OR NOT GMSH_LIBRARY)
  uhpc_missing("gmsh C++ API (gmsh.h, libgmsh)" libgmsh-dev)
endif()
add_library(uhpc_gmsh INTERFACE)
target_include_directories(uhpc_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(uhpc_gmsh INTERFACE ${GMSH_LIBRARY})
find_program(GMSH_EXECUTABLE gmsh)
if(NOT GMSH_EXECUTABLE)
  uhpc_missing("gmsh executable" gmsh)
endif()

if(UHPC_OPENMP)
  find_package(OpenMP QUIET COMPONENTS CXX)
  if(NOT OpenMP_CXX_FOUND)
    message(FATAL_ERROR "OpenMP not found for ${CMAKE_CXX_COMPILER_ID}; configure with -DUHPC_OPENMP=OFF "
                        "or install a compiler with OpenMP (bash ${UHPC_INSTALLER})")
  endif()
endif()

if(UHPC_BUILD_TESTS)
  uhpc_find_config(GTest libgtest-dev)
endif()
if(UHPC_BUILD_BENCHMARKS)
  uhpc_find_config(benchmark libbenchmark-dev)
endif()
