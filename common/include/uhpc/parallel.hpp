#pragma once
// The calling thread's place in the current OpenMP team, with the same answer (one thread, index 0)
// when the project is built without OpenMP, so code that splits work per thread needs no #ifdef.
#ifdef _OPENMP
#include <omp.h>
#endif

namespace uhpc {

inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// The threads a parallel region started here would get.
inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

inline int team_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace uhpc
