# Precompiled headers and debug information: what a clean build costs.
#
# A source of this project spends nearly all its compile time parsing
# deal.II's and Trilinos' headers: tests/contact_hertz.cc takes 14.7 s
# with -O2, of which 14.3 s is -fsyntax-only. Precompiling the headers
# used across the project parses them once per target kind (the library,
# the tests) instead of once per file.
#
# deal.II's Debian build puts -g into DEAL_II_CXX_FLAGS, which every target
# inherits through deal_ii_setup_target: with it the same file takes
# 20.6 s and its object is 17x larger. A Release build of this project has
# no debug information unless asked for (COULOMB_ADAPT_DEBUG_INFO); a
# Debug build keeps deal.II's -ggdb.

option(COULOMB_ADAPT_PRECOMPILED_HEADERS
  "Precompile the deal.II, Trilinos and standard headers (faster builds)" ON)
option(COULOMB_ADAPT_DEBUG_INFO
  "Keep deal.II's -g in a Release build (slower builds, larger objects)" OFF)

if(NOT COULOMB_ADAPT_DEBUG_INFO)
  separate_arguments(_flags UNIX_COMMAND "${DEAL_II_CXX_FLAGS}")
  list(REMOVE_ITEM _flags -g)
  list(JOIN _flags " " DEAL_II_CXX_FLAGS)
endif()

set(COULOMB_ADAPT_PRECOMPILED_HEADER_LIST
  <algorithm> <array> <cmath> <filesystem> <fstream> <functional>
  <iomanip> <iostream> <limits> <map> <memory> <optional> <set> <sstream>
  <string> <utility> <vector>
  <deal.II/base/conditional_ostream.h>
  <deal.II/base/function.h>
  <deal.II/base/index_set.h>
  <deal.II/base/mpi.h>
  <deal.II/base/parameter_handler.h>
  <deal.II/base/point.h>
  <deal.II/base/quadrature_lib.h>
  <deal.II/base/symmetric_tensor.h>
  <deal.II/base/tensor.h>
  <deal.II/base/timer.h>
  <deal.II/distributed/fully_distributed_tria.h>
  <deal.II/distributed/tria.h>
  <deal.II/dofs/dof_handler.h>
  <deal.II/dofs/dof_tools.h>
  <deal.II/fe/fe_q.h>
  <deal.II/fe/fe_simplex_p.h>
  <deal.II/fe/fe_system.h>
  <deal.II/fe/fe_values.h>
  <deal.II/fe/mapping_fe.h>
  <deal.II/grid/grid_generator.h>
  <deal.II/grid/grid_tools.h>
  <deal.II/grid/tria.h>
  <deal.II/lac/affine_constraints.h>
  <deal.II/lac/dynamic_sparsity_pattern.h>
  <deal.II/lac/full_matrix.h>
  <deal.II/lac/sparsity_tools.h>
  <deal.II/lac/trilinos_precondition.h>
  <deal.II/lac/trilinos_sparse_matrix.h>
  <deal.II/lac/trilinos_vector.h>
  <deal.II/lac/vector.h>
  <deal.II/numerics/vector_tools.h>
  <nlohmann/json.hpp>)

# Every target named here gets the precompiled headers; all but the first
# reuse the first's (they must share its flags and definitions). Sources
# with their own flags (per-file -O3) are compiled without them, since
# GCC refuses a precompiled header built with other optimisation options.
function(coulomb_adapt_precompile_headers)
  if(NOT COULOMB_ADAPT_PRECOMPILED_HEADERS OR NOT ARGN)
    return()
  endif()
  list(POP_FRONT ARGN _owner)
  target_precompile_headers(${_owner} PRIVATE
    ${COULOMB_ADAPT_PRECOMPILED_HEADER_LIST})
  foreach(_target ${ARGN})
    target_precompile_headers(${_target} REUSE_FROM ${_owner})
  endforeach()
endfunction()
