# Builds the Rust library with cargo and exposes it as the IMPORTED target igaparam::igaparam.
#
# Cargo runs on every build (it is incremental and leaves the library untouched when nothing
# changed, so dependents relink only when it did). Its target directory is inside the CMake build
# directory, away from the one `cargo` uses in the source tree.

if(NOT CMAKE_READELF)
  find_program(CMAKE_READELF readelf)
endif()

find_program(CARGO_EXECUTABLE cargo HINTS "$ENV{CARGO_HOME}/bin" "$ENV{HOME}/.cargo/bin")
if(NOT CARGO_EXECUTABLE)
  message(FATAL_ERROR "cargo not found: install Rust (https://rustup.rs) or set CARGO_EXECUTABLE")
endif()

set(IGAPARAM_CARGO_TARGET_DIR "${CMAKE_BINARY_DIR}/cargo" CACHE PATH "CARGO_TARGET_DIR of the Rust build")
set(IGAPARAM_LIBRARY
    "${IGAPARAM_CARGO_TARGET_DIR}/release/${CMAKE_SHARED_LIBRARY_PREFIX}igaparam${CMAKE_SHARED_LIBRARY_SUFFIX}")

add_custom_target(igaparam_cargo ALL
  COMMAND "${CMAKE_COMMAND}" -E env "CARGO_TARGET_DIR=${IGAPARAM_CARGO_TARGET_DIR}"
          "${CARGO_EXECUTABLE}" build --release --manifest-path "${PROJECT_SOURCE_DIR}/Cargo.toml"
  # If the library has a SONAME, programs look for that name at run time: provide it.
  COMMAND "${CMAKE_COMMAND}" "-DLIBRARY=${IGAPARAM_LIBRARY}" "-DREADELF=${CMAKE_READELF}"
          -P "${CMAKE_CURRENT_LIST_DIR}/SonameLink.cmake"
  BYPRODUCTS "${IGAPARAM_LIBRARY}"
  WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
  COMMENT "cargo build --release (igaparam)"
  USES_TERMINAL
  VERBATIM)

# IMPORTED_NO_SONAME: link with -L<dir> -ligaparam, so that programs record the library's SONAME
# if it has one, or else the name libigaparam.so (not the path used at link time), and find it
# through their RPATH.
add_library(igaparam::igaparam SHARED IMPORTED GLOBAL)
set_target_properties(igaparam::igaparam PROPERTIES
  IMPORTED_LOCATION "${IGAPARAM_LIBRARY}"
  IMPORTED_NO_SONAME TRUE
  INTERFACE_INCLUDE_DIRECTORIES "${PROJECT_SOURCE_DIR}/include")
add_dependencies(igaparam::igaparam igaparam_cargo)
