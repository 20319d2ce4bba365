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
message(STATUS "exit code ${result}: ${err}")
