# Runs igaparam_relocate and checks figures of the JSON object on the last line of its stdout.
#
#   cmake -DEXE=<igaparam_relocate> -DINPUT=<in.vtu> -DOUTPUT=<out.vtu>
#         [-DARGS=<options separated by |>] [-DCHECKS=<checks separated by |>]
#         [-DEXPECT_EXIT=<code, default 0>] -P CheckRelocate.cmake
#
# A check is <key><op><number> with op one of == != < <= > >=, e.g. `invalid_after==0` or
# `min_quality>0.2`; <key> must be a numeric member of the JSON object.

foreach(var EXE INPUT OUTPUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "CheckRelocate.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT DEFINED EXPECT_EXIT)
  set(EXPECT_EXIT 0)
endif()
string(REPLACE "|" ";" args "${ARGS}")
string(REPLACE "|" ";" checks "${CHECKS}")

get_filename_component(output_dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${output_dir}")
string(TIMESTAMP start "%s")
execute_process(
  COMMAND "${EXE}" "${INPUT}" "${OUTPUT}" ${args}
  OUTPUT_VARIABLE stdout
  RESULT_VARIABLE exit_code)  # stderr goes to the test log as it comes
string(TIMESTAMP end "%s")
message("${stdout}")
math(EXPR elapsed "${end} - ${start}")
message("exit code ${exit_code}, about ${elapsed} s")

if(NOT exit_code STREQUAL EXPECT_EXIT)
  message(FATAL_ERROR "igaparam_relocate exited with ${exit_code}, expected ${EXPECT_EXIT}")
endif()
if(NOT checks)
  return()
endif()

# The last non-empty line must be the JSON object.
include("${CMAKE_CURRENT_LIST_DIR}/LastJsonLine.cmake")
igaparam_last_json_line("${stdout}" json)

# The comparison operators and the CMake keywords that compare numbers (as doubles); != is the
# negation of EQUAL.
set(operators "==" "!=" "<=" ">=" "<" ">")
set(keywords EQUAL EQUAL LESS_EQUAL GREATER_EQUAL LESS GREATER)
set(failures "")
foreach(check IN LISTS checks)
  if(NOT check MATCHES "^([A-Za-z_]+)(==|!=|<=|>=|<|>)(.+)$")
    message(FATAL_ERROR "malformed check `${check}`")
  endif()
  set(key "${CMAKE_MATCH_1}")
  set(op "${CMAKE_MATCH_2}")
  set(expected "${CMAKE_MATCH_3}")
  if(NOT json MATCHES "\"${key}\":(-?[0-9][0-9.eE+-]*)")
    list(APPEND failures "`${key}` is missing or not a number")
    continue()
  endif()
  set(actual "${CMAKE_MATCH_1}")
  list(FIND operators "${op}" index)
  list(GET keywords ${index} keyword)
  set(holds FALSE)
  if(actual ${keyword} expected)
    set(holds TRUE)
  endif()
  if(op STREQUAL "!=")
    if(holds)
      set(holds FALSE)
    else()
      set(holds TRUE)
    endif()
  endif()
  if(holds)
    message("ok: ${key} = ${actual} (${op} ${expected})")
  else()
    list(APPEND failures "${key} = ${actual}, expected ${op} ${expected}")
  endif()
endforeach()

if(failures)
  string(REPLACE ";" "\n  " failures "${failures}")
  message(FATAL_ERROR "checks failed:\n  ${failures}")
endif()
