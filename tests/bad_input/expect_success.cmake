# Run EXE with ARGS (a ;-list) on RANKS MPI processes (MPIEXEC); succeed
# only if it exits with 0 and its standard output matches the regular
# expression EXPECTED (the numbers it must print).
# PREVIOUS_ARGS (optional): a run before, with these arguments instead.
# ABSENT (optional): a ;-list of glob patterns that must match no file
# afterwards. UNEXPECTED (optional): a regular expression the standard
# output must not match (a warning that must be gone). A claimed bound
# below the run's exact error fails unless EXPECTED names it.
set(launcher)
if(DEFINED RANKS)
  set(launcher ${MPIEXEC} -np ${RANKS})
endif()
if(DEFINED PREVIOUS_ARGS)
  execute_process(COMMAND ${launcher} ${EXE} ${PREVIOUS_ARGS}
    RESULT_VARIABLE previous_result OUTPUT_QUIET ERROR_VARIABLE previous_err)
  if(NOT previous_result EQUAL 0)
    message(FATAL_ERROR "the previous run failed: ${previous_err}")
  endif()
endif()
execute_process(COMMAND ${launcher} ${EXE} ${ARGS}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "expected exit code 0, got ${result}:\n${out}\n${err}")
endif()
string(REPLACE "\n" " " out_one_line "${out}")
if(NOT out_one_line MATCHES "${EXPECTED}")
  message(FATAL_ERROR "the output does not match\n  '${EXPECTED}':\n${out}")
endif()
# A run that computes its exact error checks the bound it claims
# (CycleReport::record_claimed_bound): its warning fails every test that
# does not expect it.
if(out_one_line MATCHES "below the exact error it claims to bound" AND
   NOT EXPECTED MATCHES "below the exact error it claims to bound")
  message(FATAL_ERROR "a claimed bound is below the exact error:\n${out}")
endif()
if(DEFINED UNEXPECTED AND out_one_line MATCHES "${UNEXPECTED}")
  message(FATAL_ERROR "the output matches '${UNEXPECTED}', which it must not:\n${out}")
endif()
foreach(pattern ${ABSENT})
  file(GLOB left ${pattern})
  if(left)
    message(FATAL_ERROR "these files were left: ${left}")
  endif()
endforeach()
string(REGEX MATCH "${EXPECTED}" matched "${out_one_line}")
message(STATUS "matched: ${matched}")
