# Writes OUTPUT_FILE defining coulomb_adapt::version() from `git describe`;
# the file is only touched when the string changes, so builds stay incremental.
execute_process(
  COMMAND git describe --always --dirty --tags
  WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_VARIABLE _describe
  OUTPUT_STRIP_TRAILING_WHITESPACE
  ERROR_QUIET
  RESULT_VARIABLE _result)
if(NOT _result EQUAL 0 OR "${_describe}" STREQUAL "")
  set(_describe "unknown")
endif()
set(_content "#include <coulomb_adapt/core/version.h>\nnamespace coulomb_adapt\n{\n  std::string\n  version()\n  {\n    return \"${_describe}\";\n  }\n} // namespace coulomb_adapt\n")
if(EXISTS ${OUTPUT_FILE})
  file(READ ${OUTPUT_FILE} _old)
else()
  set(_old "")
endif()
if(NOT "${_old}" STREQUAL "${_content}")
  file(WRITE ${OUTPUT_FILE} "${_content}")
endif()
