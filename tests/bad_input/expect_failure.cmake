# Run EXE with ARGS (a ;-list); succeed only if it fails (exit code != 0)
# and its standard error matches the regular expression EXPECTED.
# MAKE_DIRECTORY (optional): a directory created first, to stand in the
# way of an output file.
# MPIEXEC and RANKS (optional): run on RANKS MPI processes.
# FULL_FILE (optional): a fresh directory with FULL_FILE in it a symbolic
# link to /dev/full, where every write fails with "No space left on
# device": a full disk for exactly one file.
# MAKE_FIFO (optional): a named pipe created first (removed if there).
# ABSENT (optional): a ;-list of glob patterns that must match no file
# afterwards (nothing half-written left behind).
# NOT_IN_FILE (optional): FILE;REGEX;FILE;REGEX..., files whose contents
# each REGEX must not match afterwards (an index that must not list a
# cycle; a missing file lists nothing).
# IN_FILE (optional): FILE;REGEX;FILE;REGEX..., files whose contents
# each REGEX must match afterwards (an index that must list a cycle).
# SUMMARY (optional): the run's summary.json, which must say so:
# status "failed", an error matching EXPECTED, failed_in_cycle equal to
# FAILED_IN_CYCLE, and the FAILED_IN_CYCLE cycles before it kept.
if(DEFINED MAKE_DIRECTORY)
  file(MAKE_DIRECTORY ${MAKE_DIRECTORY})
endif()
if(DEFINED FULL_FILE)
  get_filename_component(full_directory ${FULL_FILE} DIRECTORY)
  file(REMOVE_RECURSE ${full_directory})
  file(MAKE_DIRECTORY ${full_directory})
  file(CREATE_LINK /dev/full ${FULL_FILE} SYMBOLIC)
endif()
if(DEFINED MAKE_FIFO)
  file(REMOVE ${MAKE_FIFO})
  execute_process(COMMAND mkfifo ${MAKE_FIFO})
endif()
set(launcher)
if(DEFINED RANKS)
  set(launcher ${MPIEXEC} -np ${RANKS})
endif()
execute_process(COMMAND ${launcher} ${EXE} ${ARGS}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(result EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit code; output:\n${out}\n${err}")
endif()
string(REPLACE "\n" " " err_one_line "${err}")
if(NOT err_one_line MATCHES "${EXPECTED}")
  message(FATAL_ERROR "exit code ${result}, but the message does not match\n  '${EXPECTED}':\n${err}")
endif()
foreach(pattern ${ABSENT})
  file(GLOB left ${pattern})
  if(left)
    message(FATAL_ERROR "exit code ${result}, but these files were left: ${left}")
  endif()
endforeach()
# FILE;REGEX pairs of @p pairs: each FILE's contents must match REGEX
# (@p must_match) or must not (a missing file then matches nothing).
function(check_file_contents pairs must_match)
  list(LENGTH pairs n)
  math(EXPR last_pair "${n} - 2")
  foreach(i RANGE 0 ${last_pair} 2)
    math(EXPR j "${i} + 1")
    list(GET pairs ${i} checked_file)
    list(GET pairs ${j} checked_regex)
    set(checked_contents "")
    if(EXISTS ${checked_file})
      file(READ ${checked_file} checked_contents)
    elseif(must_match)
      message(FATAL_ERROR "exit code ${result}, but ${checked_file} is missing")
    endif()
    if(checked_contents MATCHES "${checked_regex}")
      set(matches TRUE)
    else()
      set(matches FALSE)
    endif()
    if(NOT matches STREQUAL must_match)
      message(FATAL_ERROR "exit code ${result}, but ${checked_file} matches '${checked_regex}': ${matches}, expected ${must_match}:\n${checked_contents}")
    endif()
  endforeach()
endfunction()
if(DEFINED NOT_IN_FILE)
  check_file_contents("${NOT_IN_FILE}" FALSE)
endif()
if(DEFINED IN_FILE)
  check_file_contents("${IN_FILE}" TRUE)
endif()
if(DEFINED SUMMARY)
  file(READ ${SUMMARY} summary)
  string(JSON status GET "${summary}" status)
  string(JSON error GET "${summary}" error)
  string(JSON failed_in_cycle GET "${summary}" failed_in_cycle)
  string(JSON n_cycles LENGTH "${summary}" cycles)
  string(REPLACE "\n" " " error_one_line "${error}")
  if(NOT status STREQUAL "failed" OR NOT error_one_line MATCHES "${EXPECTED}"
     OR NOT failed_in_cycle EQUAL FAILED_IN_CYCLE
     OR NOT n_cycles EQUAL FAILED_IN_CYCLE)
    message(FATAL_ERROR "${SUMMARY} does not record the failure: status '${status}', failed_in_cycle ${failed_in_cycle} (expected ${FAILED_IN_CYCLE}), ${n_cycles} cycles kept, error '${error}'")
  endif()
endif()
message(STATUS "exit code ${result}: ${err}")
