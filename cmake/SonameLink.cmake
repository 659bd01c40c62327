# cmake -DLIBRARY=<shared library> -DREADELF=<readelf> -P SonameLink.cmake
#
# If LIBRARY is an ELF file with a SONAME other than its file name (e.g. libigaparam.so.0 for
# libigaparam.so), creates a symbolic link of that name next to it: a program linked against the
# library records the SONAME and looks for it, through its RPATH, in that directory.

if(NOT DEFINED LIBRARY OR NOT EXISTS "${LIBRARY}")
  message(FATAL_ERROR "SonameLink.cmake: LIBRARY (${LIBRARY}) does not exist")
endif()

file(READ "${LIBRARY}" magic LIMIT 4 HEX)
if(NOT magic STREQUAL "7f454c46") # not ELF
  return()
endif()
if(NOT READELF)
  message(WARNING "SonameLink.cmake: no readelf; if ${LIBRARY} has a SONAME, programs will not find it")
  return()
endif()

execute_process(COMMAND "${READELF}" -d "${LIBRARY}" OUTPUT_VARIABLE dynamic RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "SonameLink.cmake: ${READELF} -d ${LIBRARY} failed")
endif()
# A line of the form: 0x000000000000000e (SONAME)  Library soname: [libigaparam.so.0]
if(dynamic MATCHES "\\(SONAME\\)[^[]*\\[([^]]+)\\]")
  set(soname "${CMAKE_MATCH_1}")
  get_filename_component(directory "${LIBRARY}" DIRECTORY)
  get_filename_component(name "${LIBRARY}" NAME)
  if(NOT soname STREQUAL name)
    file(CREATE_LINK "${name}" "${directory}/${soname}" SYMBOLIC)
  endif()
endif()
