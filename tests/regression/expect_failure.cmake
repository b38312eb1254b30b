# cmake -DCOMMAND="prog|arg|..." -DEXPECTED_CODE=2 -DEXPECTED_STDERR="exact line" -P expect_failure.cmake
# Runs COMMAND and passes only if it exits with EXPECTED_CODE and its stderr is exactly
# EXPECTED_STDERR (one line, trailing newline ignored): the bad-input contract of every program.
# With -DEXPECTED_FILE=path -DEXPECTED_FILE_TEXT=text it also needs the file (a numerical failure's
# diagnostic) to exist and to hold that text.
string(REPLACE "|" ";" COMMAND "${COMMAND}")
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(NOT code STREQUAL EXPECTED_CODE)
  message(FATAL_ERROR "exit code ${code}, expected ${EXPECTED_CODE}; stderr: ${err}")
endif()
if(NOT err STREQUAL EXPECTED_STDERR)
  message(FATAL_ERROR "stderr was\n  ${err}\nexpected\n  ${EXPECTED_STDERR}")
endif()
if(DEFINED EXPECTED_FILE)
  if(NOT EXISTS "${EXPECTED_FILE}")
    message(FATAL_ERROR "${EXPECTED_FILE} was not written")
  endif()
  file(READ "${EXPECTED_FILE}" content)
  string(FIND "${content}" "${EXPECTED_FILE_TEXT}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${EXPECTED_FILE} does not hold '${EXPECTED_FILE_TEXT}'")
  endif()
endif()
message(STATUS "exit ${code}: ${err}")
