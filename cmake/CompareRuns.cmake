# Runs one program with different thread counts and checks that the JSON objects on the last
# lines of their outputs are the same, apart from the `"threads": N` and `"seconds": T` members
# (the latter a wall time), and, with FILES, that the files each run wrote are the same byte for
# byte.
#
#   cmake -DEXE=<program> -DARGS=<options separated by |> -DTHREADS=<n1|n2|...>
#         [-DFILES=<paths separated by |>] [-DMATCH=<regex every JSON line must match>]
#         -P CompareRuns.cmake
#
# `{threads}` in ARGS and FILES stands for the run's thread count, so that each run writes its
# own files.

foreach(var EXE ARGS THREADS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "CompareRuns.cmake: ${var} is not set")
  endif()
endforeach()
include("${CMAKE_CURRENT_LIST_DIR}/LastJsonLine.cmake")
string(REPLACE "|" ";" threads "${THREADS}")
string(REPLACE "|" ";" files "${FILES}")
set(lines "")
foreach(n IN LISTS threads)
  string(REPLACE "{threads}" "${n}" run_args "${ARGS}")
  string(REPLACE "|" ";" run_args "${run_args}")
  foreach(file IN LISTS files)
    string(REPLACE "{threads}" "${n}" file "${file}")
    file(REMOVE "${file}")
  endforeach()
  execute_process(COMMAND "${EXE}" ${run_args} --threads ${n} OUTPUT_VARIABLE stdout RESULT_VARIABLE code)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${EXE} with --threads ${n} exited with ${code}:\n${stdout}")
  endif()
  igaparam_last_json_line("${stdout}" json)
  if(DEFINED MATCH AND NOT json MATCHES "${MATCH}")
    message(FATAL_ERROR "--threads ${n}: the output does not match `${MATCH}`:\n${json}")
  endif()
  string(REGEX REPLACE "\"threads\": *[0-9]+" "\"threads\": _" json "${json}")
  string(REGEX REPLACE "\"seconds\": *[0-9.eE+-]+" "\"seconds\": _" json "${json}")
  message("--threads ${n}: ${json}")
  list(APPEND lines "${json}")
endforeach()
list(GET lines 0 first)
foreach(line IN LISTS lines)
  if(NOT line STREQUAL first)
    message(FATAL_ERROR "the runs differ")
  endif()
endforeach()
list(GET threads 0 n0)
foreach(file IN LISTS files)
  string(REPLACE "{threads}" "${n0}" reference "${file}")
  foreach(n IN LISTS threads)
    string(REPLACE "{threads}" "${n}" other "${file}")
    execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${reference}" "${other}" RESULT_VARIABLE differ)
    if(NOT differ EQUAL 0)
      message(FATAL_ERROR "${other} differs from ${reference} (or is missing)")
    endif()
  endforeach()
  message("${file}: the same bytes at every thread count")
endforeach()
