# Version and git commit for the provenance block. The commit is re-read at every build (not only at
# configure time) but the generated file changes only when the commit does, so nothing recompiles
# needlessly.
set(UHPC_BUILD_INFO_CPP ${CMAKE_CURRENT_BINARY_DIR}/generated/build_info.cpp)
add_custom_target(uhpc_build_info_refresh
  COMMAND ${CMAKE_COMMAND}
          -DSOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR}
          -DOUTPUT=${UHPC_BUILD_INFO_CPP}
          -DVERSION=${PROJECT_VERSION}
          -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/WriteBuildInfo.cmake
  BYPRODUCTS ${UHPC_BUILD_INFO_CPP}
  COMMENT "Reading the git commit for provenance")
