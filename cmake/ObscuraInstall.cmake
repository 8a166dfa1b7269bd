# `cmake --install` and the Debian package: the layout an integrator consumes.
#   bin/obscura                               the harness; finds the plugin below with no environment variable
#   lib/obscura/plugin/obscura/               the plugin library and its generated plugInfo.json
#   include/obscura/                          the public C ABI header(s)
#   lib/cmake/Obscura/                        find_package(Obscura CONFIG): Obscura::headers, Obscura_PLUGIN_DIR
#   lib/pkgconfig/obscura.pc                  pkg-config --cflags obscura; --variable=plugindir obscura
#   lib/python3/dist-packages/obscura/        the Python package
include(CMakePackageConfigHelpers)
set(OBSCURA_CMAKE_PACKAGE_DIR lib/cmake/Obscura)
set(OBSCURA_PKGCONFIG_DIR lib/pkgconfig)

install(TARGETS obscura RUNTIME DESTINATION bin COMPONENT runtime)
install(TARGETS obscura_plugin LIBRARY DESTINATION ${OBSCURA_PLUGIN_RELDIR}/obscura COMPONENT runtime)
install(FILES ${OBSCURA_PLUGIN_DIR}/plugInfo.json DESTINATION ${OBSCURA_PLUGIN_RELDIR}/obscura COMPONENT runtime)
install(DIRECTORY include/obscura DESTINATION include COMPONENT development)
# The Python package (docs/PYTHON.md), where Debian's python3 looks under /usr; it finds the plugin
# relative to itself (<prefix>/lib/python3/dist-packages/obscura -> <prefix>/lib/obscura/plugin).
install(DIRECTORY python/obscura DESTINATION lib/python3/dist-packages COMPONENT runtime PATTERN __pycache__ EXCLUDE)

configure_package_config_file(cmake/package/ObscuraConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/ObscuraConfig.cmake
  INSTALL_DESTINATION ${OBSCURA_CMAKE_PACKAGE_DIR}
  PATH_VARS OBSCURA_PLUGIN_RELDIR)
# The ABI's major version is the compatibility line: a host built for 1.x works with any 1.y, y >= x.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/ObscuraConfigVersion.cmake
  VERSION ${OBSCURA_ABI_MAJOR}.${OBSCURA_ABI_MINOR}
  COMPATIBILITY SameMajorVersion ARCH_INDEPENDENT)
install(FILES ${CMAKE_BINARY_DIR}/package/ObscuraConfig.cmake ${CMAKE_BINARY_DIR}/package/ObscuraConfigVersion.cmake
  DESTINATION ${OBSCURA_CMAKE_PACKAGE_DIR} COMPONENT development)
configure_file(cmake/package/obscura.pc.in ${CMAKE_BINARY_DIR}/package/obscura.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/package/obscura.pc DESTINATION ${OBSCURA_PKGCONFIG_DIR} COMPONENT development)

# CPack: a Debian package of the same layout under /usr (`cpack -G DEB` in the build folder).
set(CPACK_PACKAGE_NAME obscura)
set(CPACK_PACKAGE_VENDOR "Obscura")
set(CPACK_PACKAGE_CONTACT "Obscura maintainers <obscura@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Vulkan deferred renderer as a Hydra-style render delegate plugin")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_STRIP_FILES ON)
# Library dependencies from the binaries themselves (dpkg-shlibdeps); a Vulkan driver beside them,
# lavapipe where nothing else provides one.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The tools cpack runs for that (`file`, dpkg-shlibdeps), found at configure time too so that
# tests/setup/setup_covers_build.py sees them in the cache and checks their packages are listed.
find_program(OBSCURA_CPACK_FILE_PROGRAM file)
find_program(OBSCURA_CPACK_SHLIBDEPS_PROGRAM dpkg-shlibdeps)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "mesa-vulkan-drivers | vulkan-icd")
include(CPack)
