# Install rules: `cmake --install <build> [--prefix <prefix>]` installs
#
#   <libdir>/libigaparam.so.<version>, with the links libigaparam.so.<major> (the SONAME) and
#     libigaparam.so (for -ligaparam) on ELF platforms;
#   <includedir>/igaparam.h and <includedir>/igaparam.hpp, igaparam_spline.hpp (the C++17 wrapper);
#   <libdir>/cmake/igaparam/igaparamConfig.cmake and igaparamConfigVersion.cmake, giving the
#     IMPORTED targets igaparam::igaparam and igaparam::cpp to find_package(igaparam);
#   <libdir>/pkgconfig/igaparam.pc.
#
# Every installed path is relative to the prefix chosen at install time (the package config and
# the pkg-config file locate the prefix from their own place), so --prefix and DESTDIR work.

include(CMakePackageConfigHelpers)

set(IGAPARAM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/igaparam" CACHE STRING
    "Where the CMake package configuration is installed, relative to the prefix")
set(IGAPARAM_INSTALL_PKGCONFIGDIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig" CACHE STRING
    "Where igaparam.pc is installed, relative to the prefix")
foreach(dir CMAKE_INSTALL_LIBDIR CMAKE_INSTALL_INCLUDEDIR IGAPARAM_INSTALL_CMAKEDIR IGAPARAM_INSTALL_PKGCONFIGDIR)
  if(IS_ABSOLUTE "${${dir}}")
    message(FATAL_ERROR "${dir} (${${dir}}) must be relative to the install prefix")
  endif()
endforeach()

# The library: on ELF platforms the file is named after the full version and carries the SONAME
# libigaparam.so.<major> (set by build.rs).
get_filename_component(_igaparam_built_name "${IGAPARAM_LIBRARY}" NAME)
if(CMAKE_SYSTEM_NAME MATCHES "Linux|BSD|DragonFly")
  set(IGAPARAM_INSTALLED_LIBRARY_NAME "${_igaparam_built_name}.${PROJECT_VERSION}")
  set(IGAPARAM_INSTALLED_SONAME "${_igaparam_built_name}.${PROJECT_VERSION_MAJOR}")
else()
  set(IGAPARAM_INSTALLED_LIBRARY_NAME "${_igaparam_built_name}")
  set(IGAPARAM_INSTALLED_SONAME "")
endif()

install(PROGRAMS "${IGAPARAM_LIBRARY}"
  DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  RENAME "${IGAPARAM_INSTALLED_LIBRARY_NAME}")
if(IGAPARAM_INSTALLED_SONAME)
  # The links, relative to the library's directory, created when installing.
  install(CODE "
    set(_dir \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}\")
    foreach(_link \"${IGAPARAM_INSTALLED_SONAME}\" \"${_igaparam_built_name}\")
      message(STATUS \"Installing: \${_dir}/\${_link} -> ${IGAPARAM_INSTALLED_LIBRARY_NAME}\")
      file(REMOVE \"\${_dir}/\${_link}\")
      file(CREATE_LINK \"${IGAPARAM_INSTALLED_LIBRARY_NAME}\" \"\${_dir}/\${_link}\" SYMBOLIC)
    endforeach()
  ")
endif()

install(FILES include/igaparam.h bindings/cpp/igaparam.hpp bindings/cpp/igaparam_spline.hpp DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")

# CMake package.
configure_package_config_file(cmake/igaparamConfig.cmake.in
  "${PROJECT_BINARY_DIR}/igaparamConfig.cmake"
  INSTALL_DESTINATION "${IGAPARAM_INSTALL_CMAKEDIR}"
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR CMAKE_INSTALL_LIBDIR)
write_basic_package_version_file("${PROJECT_BINARY_DIR}/igaparamConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/igaparamConfig.cmake" "${PROJECT_BINARY_DIR}/igaparamConfigVersion.cmake"
  DESTINATION "${IGAPARAM_INSTALL_CMAKEDIR}")

# pkg-config file; its prefix is found from its own directory (${pcfiledir}).
file(RELATIVE_PATH IGAPARAM_PC_PREFIX_FROM_PCDIR "/prefix/${IGAPARAM_INSTALL_PKGCONFIGDIR}" "/prefix")
string(REGEX REPLACE "/$" "" IGAPARAM_PC_PREFIX_FROM_PCDIR "${IGAPARAM_PC_PREFIX_FROM_PCDIR}")
if(IGAPARAM_PC_PREFIX_FROM_PCDIR STREQUAL "")
  set(IGAPARAM_PC_PREFIX_FROM_PCDIR ".")
endif()
configure_file(cmake/igaparam.pc.in "${PROJECT_BINARY_DIR}/igaparam.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/igaparam.pc" DESTINATION "${IGAPARAM_INSTALL_PKGCONFIGDIR}")
