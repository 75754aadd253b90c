# The installed package: the program, the static libraries with their headers
# under include/passtrace/ (named as in the source tree: "accel/kd/kd_tree.h"),
# the kernels for reading, and a config so that another project's
#   find_package(passtrace CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE passtrace::passtrace)
# works. tests/package_consumer/ checks exactly that (ctest -R InstalledPackage).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PASSTRACE_INCLUDE_DIR ${CMAKE_INSTALL_INCLUDEDIR}/passtrace)
set(PASSTRACE_CONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/passtrace)

install(TARGETS passtrace RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET passtrace_oiio)  # the image formats but OpenEXR, loaded at run time (render/oiio_module.h)
  install(TARGETS passtrace_oiio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/passtrace)
endif()
install(TARGETS passtrace_geometry passtrace_glad passtrace_stream passtrace_scenes passtrace_accel passtrace_lib
  EXPORT passtraceTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  FILE_SET HEADERS DESTINATION ${PASSTRACE_INCLUDE_DIR}
  FILE_SET generated DESTINATION ${PASSTRACE_INCLUDE_DIR}
  INCLUDES DESTINATION ${PASSTRACE_INCLUDE_DIR})
# glad's generated headers (glad/gl.h, KHR/khrplatform.h): stream/gl.h includes them.
install(DIRECTORY ${PASSTRACE_GLAD_INCLUDE_DIR}/ DESTINATION ${PASSTRACE_INCLUDE_DIR})
# Embedded in the library at build time; installed to be read.
install(DIRECTORY kernels_glsl/ DESTINATION ${CMAKE_INSTALL_DATADIR}/passtrace/kernels_glsl)

install(EXPORT passtraceTargets NAMESPACE passtrace:: DESTINATION ${PASSTRACE_CONFIG_DIR})
configure_package_config_file(cmake/passtraceConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/passtraceConfig.cmake
  INSTALL_DESTINATION ${PASSTRACE_CONFIG_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/passtraceConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)  # 0.x: a minor release may break the API
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/passtraceConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/passtraceConfigVersion.cmake
  DESTINATION ${PASSTRACE_CONFIG_DIR})
