# Installing pcsim as a library of the field: the pcsim command, the pagecache library (static,
# or shared with BUILD_SHARED_LIBS), its public headers, a CMake package (from the install tree
# and from the build tree), a pkg-config file, and pcsim's data under DATADIR/pcsim. Checked by
# tests/consumer (both trees, static and shared, pkg-config) and tests/package (the .deb).
include(CMakePackageConfigHelpers)

install(TARGETS pagecache EXPORT pagecacheTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/pagecache DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES ${PROJECT_BINARY_DIR}/include/pagecache/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pagecache)

# The CMake package: find_package(pagecache) with CMAKE_PREFIX_PATH=PREFIX, or
# pagecache_DIR=BUILD_TREE for a build not installed.
set(pagecache_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/pagecache)
install(EXPORT pagecacheTargets NAMESPACE pagecache:: DESTINATION ${pagecache_cmake_dir})
export(EXPORT pagecacheTargets NAMESPACE pagecache:: FILE ${PROJECT_BINARY_DIR}/pagecacheTargets.cmake)
configure_package_config_file(cmake/pagecacheConfig.cmake.in
  ${PROJECT_BINARY_DIR}/pagecacheConfig.cmake
  INSTALL_DESTINATION ${pagecache_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pagecacheConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pagecacheConfig.cmake ${PROJECT_BINARY_DIR}/pagecacheConfigVersion.cmake
        DESTINATION ${pagecache_cmake_dir})

# pkg-config: paths relative to the .pc file's own folder, so that the prefix may be moved. A
# static library needs its dependencies on every link line; a shared one links them itself.
file(RELATIVE_PATH PAGECACHE_PC_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" PAGECACHE_PC_PREFIX "${PAGECACHE_PC_PREFIX}")
file(RELATIVE_PATH PAGECACHE_PC_LIBDIR ${CMAKE_INSTALL_PREFIX} ${CMAKE_INSTALL_FULL_LIBDIR})
file(RELATIVE_PATH PAGECACHE_PC_INCLUDEDIR ${CMAKE_INSTALL_PREFIX} ${CMAKE_INSTALL_FULL_INCLUDEDIR})
if(BUILD_SHARED_LIBS)
  set(PAGECACHE_PC_REQUIRES "Requires.private")
else()
  set(PAGECACHE_PC_REQUIRES "Requires")
endif()
configure_file(cmake/pagecache.pc.in ${PROJECT_BINARY_DIR}/pagecache.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/pagecache.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The command and the data it finds beside itself (cmake/DataDir.cmake); with a shared library,
# pcsim finds it relative to itself too.
if(TARGET pcsim)
  if(BUILD_SHARED_LIBS)
    file(RELATIVE_PATH pcsim_lib_from_bin ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
    set_target_properties(pcsim PROPERTIES INSTALL_RPATH "$ORIGIN/${pcsim_lib_from_bin}")
  endif()
  install(TARGETS pcsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
foreach(folder IN LISTS PCSIM_DATA_FOLDERS)
  install(DIRECTORY ${folder} DESTINATION ${CMAKE_INSTALL_DATADIR}/pcsim)
endforeach()
install(FILES LICENSE CITATION.cff README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
