# Runs igaparam_relocate_mpi on INPUT serially (--serial) and under mpirun at each rank count of
# RANKS, and checks that every run exits 0 (a valid mesh) and prints the serial run's checksum
# (the positions are the same bit for bit).
#
#   cmake -DEXE=<program> -DMPIEXEC=<mpirun> -DMPIEXEC_FLAGS=<flags separated by |>
#         -DINPUT=<in.vtu> -DOUTPUT=<output prefix> -DRANKS=<counts separated by |>
#         [-DARGS=<options separated by |>] -P CompareMpi.cmake

foreach(var EXE MPIEXEC INPUT OUTPUT RANKS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "CompareMpi.cmake: ${var} is not set")
  endif()
endforeach()
string(REPLACE "|" ";" args "${ARGS}")
string(REPLACE "|" ";" flags "${MPIEXEC_FLAGS}")
string(REPLACE "|" ";" ranks "${RANKS}")
get_filename_component(output_dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${output_dir}")

# Runs the command, checks its exit code, returns the checksum of its last JSON line.
function(checksum_of out)
  execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE stdout RESULT_VARIABLE code)
  message("${stdout}")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "exit code ${code} from: ${ARGN}")
  endif()
  if(NOT stdout MATCHES "\"invalid_after\": 0,")
    message(FATAL_ERROR "the relocated mesh is not valid")
  endif()
  if(NOT stdout MATCHES "\"checksum\": \"([0-9a-f]+)\"")
    message(FATAL_ERROR "no checksum in the output")
  endif()
  set(${out} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

checksum_of(serial "${EXE}" "${INPUT}" - --serial ${args})
foreach(n IN LISTS ranks)
  checksum_of(sum "${MPIEXEC}" ${flags} -np ${n} "${EXE}" "${INPUT}" "${OUTPUT}_${n}.pvtu"
              --gather "${OUTPUT}_${n}_whole.vtu" ${args})
  if(NOT sum STREQUAL serial)
    message(FATAL_ERROR "${n} ranks: checksum ${sum}, the serial run's is ${serial}")
  endif()
  message("${n} ranks: the same positions as the serial run")
endforeach()
