include(CMakePackageConfigHelpers)
install(TARGETS inertest EXPORT inertestTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS inertest_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/inertest DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT inertestTargets NAMESPACE inertest:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/inertest)
configure_package_config_file(cmake/inertestConfig.cmake.in
  ${PROJECT_BINARY_DIR}/inertestConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/inertest)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/inertestConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/inertestConfig.cmake ${PROJECT_BINARY_DIR}/inertestConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/inertest)
