# Installs an igaparam build into a temporary prefix, then builds and runs the project in this
# directory against it with find_package(igaparam), and main.c with pkg-config's flags.
#
#   cmake -DBUILD_DIR=<igaparam build> -DSOURCE_DIR=<this directory> -DWORK_DIR=<scratch dir>
#         [-DGENERATOR=<generator>] [-DC_COMPILER=<cc>] [-DCXX_COMPILER=<c++>]
#         [-DPKG_CONFIG=<pkg-config>] [-DVERSION=<expected version>] -P run_consumer.cmake

foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake: ${var} is not set")
  endif()
endforeach()

# Runs a command, echoing it; fails the test if it fails.
function(run)
  string(REPLACE ";" " " shown "${ARGN}")
  message("+ ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "command failed (${failed}): ${shown}")
  endif()
endfunction()

set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# 1. Install, and check the installed files.
run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
set(lib "${prefix}/lib")
foreach(file
    "${lib}/libigaparam.so.${VERSION}"
    "include/igaparam.h" "include/igaparam.hpp" "include/igaparam_spline.hpp"
    "lib/cmake/igaparam/igaparamConfig.cmake" "lib/cmake/igaparam/igaparamConfigVersion.cmake"
    "lib/pkgconfig/igaparam.pc")
  if(NOT IS_ABSOLUTE "${file}")
    set(file "${prefix}/${file}")
  endif()
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()
string(REGEX MATCH "^[0-9]+" major "${VERSION}")
foreach(link "libigaparam.so.${major}" "libigaparam.so")
  if(NOT IS_SYMLINK "${lib}/${link}")
    message(FATAL_ERROR "not a symbolic link: ${lib}/${link}")
  endif()
  file(READ_SYMLINK "${lib}/${link}" target)
  if(NOT target STREQUAL "libigaparam.so.${VERSION}")
    message(FATAL_ERROR "${lib}/${link} -> ${target}, expected libigaparam.so.${VERSION}")
  endif()
endforeach()
message("installed files: ok")

# 2. find_package(igaparam 0.1 REQUIRED) in an outside project; its programs find the library
#    through the RPATH CMake gives them in the build tree.
set(generator_args "")
if(GENERATOR)
  list(APPEND generator_args -G "${GENERATOR}")
endif()
if(C_COMPILER)
  list(APPEND generator_args "-DCMAKE_C_COMPILER=${C_COMPILER}")
endif()
if(CXX_COMPILER)
  list(APPEND generator_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" ${generator_args}
    "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/consumer_c")
run("${WORK_DIR}/build/consumer_cpp")

# 3. pkg-config: cc main.c $(pkg-config --cflags --libs igaparam).
if(NOT PKG_CONFIG)
  message(FATAL_ERROR "pkg-config not found")
endif()
set(ENV{PKG_CONFIG_PATH} "${lib}/pkgconfig")
execute_process(COMMAND "${PKG_CONFIG}" --cflags --libs igaparam
  OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "pkg-config --cflags --libs igaparam failed")
endif()
message("pkg-config --cflags --libs igaparam: ${flags}")
execute_process(COMMAND "${PKG_CONFIG}" --modversion igaparam
  OUTPUT_VARIABLE modversion OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT modversion STREQUAL VERSION)
  message(FATAL_ERROR "pkg-config --modversion igaparam: ${modversion}, expected ${VERSION}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
if(NOT C_COMPILER)
  set(C_COMPILER cc)
endif()
run("${C_COMPILER}" "${SOURCE_DIR}/main.c" ${flags} -o "${WORK_DIR}/consumer_pkgconfig")
set(ENV{LD_LIBRARY_PATH} "${lib}")
run("${WORK_DIR}/consumer_pkgconfig")
message("cmake package consumer: ok")
