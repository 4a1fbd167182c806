# Install the library, its public headers and a CMake package, so that another project can
# find_package(pagecache) and link pagecache::pagecache (checked by tests/consumer).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS pagecache EXPORT pagecacheTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/pagecache DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/include/pagecache/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pagecache)
install(EXPORT pagecacheTargets NAMESPACE pagecache::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pagecache)
configure_package_config_file(cmake/pagecacheConfig.cmake.in
  ${PROJECT_BINARY_DIR}/pagecacheConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pagecache)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pagecacheConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pagecacheConfig.cmake ${PROJECT_BINARY_DIR}/pagecacheConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pagecache)
if(TARGET pcsim)
  install(TARGETS pcsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
