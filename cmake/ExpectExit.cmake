# Runs a command and checks its exact exit code and, optionally, that its standard error (or
# output) matches a regular expression: a failing program must fail for the expected reason (a
# usage error exits 2, a refused input 1), not merely exit non-zero.
#
#   cmake "-DCOMMAND=<program|arg|...>" -DEXPECT_EXIT=<code> [-DEXPECT_MESSAGE=<regex>]
#         -P ExpectExit.cmake

foreach(var COMMAND EXPECT_EXIT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "ExpectExit.cmake: ${var} is not set")
  endif()
endforeach()
string(REPLACE "|" ";" command "${COMMAND}")
execute_process(COMMAND ${command} OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr RESULT_VARIABLE code)
message("${stdout}${stderr}exit code ${code}")
if(NOT code STREQUAL EXPECT_EXIT)
  message(FATAL_ERROR "exited with ${code}, expected ${EXPECT_EXIT}")
endif()
if(DEFINED EXPECT_MESSAGE AND NOT "${stderr}${stdout}" MATCHES "${EXPECT_MESSAGE}")
  message(FATAL_ERROR "the output does not match `${EXPECT_MESSAGE}`")
endif()
