# Installing pcsim as a library of the field: the pcsim command, the pagecache library (static,
# or shared with BUILD_SHARED_LIBS), its public headers, a CMake package (from the install tree
# and from the build tree), a pkg-config file, and pcsim's data under DATADIR/pcsim. Checked by
# tests/consumer (both trees, static and shared, pkg-config) and tests/package (the .deb).
include(CMakePackageConfigHelpers)

# pagecache_install(LIBRARY lib PROGRAM pcsim EXPORT set CONFIG_DIR dir [SHARED] [COMPONENT c])
# The rules of one installed flavour; CONFIG_DIR receives its build-tree package files. With a
# COMPONENT, the rules run only for `cmake --install --component c` (the shared twin below).
function(pagecache_install)
  cmake_parse_arguments(I "SHARED" "LIBRARY;PROGRAM;EXPORT;CONFIG_DIR;COMPONENT" "" ${ARGN})
  set(only "")
  if(I_COMPONENT)
    set(only COMPONENT ${I_COMPONENT} EXCLUDE_FROM_ALL)
  endif()
  install(TARGETS ${I_LIBRARY} EXPORT ${I_EXPORT} ${only}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY include/pagecache DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} ${only})
  install(FILES ${PROJECT_BINARY_DIR}/include/pagecache/version.hpp
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pagecache ${only})

  # The CMake package: find_package(pagecache) with CMAKE_PREFIX_PATH=PREFIX, or
  # pagecache_DIR=CONFIG_DIR for a build not installed.
  set(cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/pagecache)
  # Each flavour's targets file has its export set's name: CMake stages an installed export by
  # destination and file name, so two flavours sharing both would overwrite each other.
  set(PAGECACHE_TARGETS_FILE ${I_EXPORT}.cmake)
  install(EXPORT ${I_EXPORT} NAMESPACE pagecache:: FILE ${PAGECACHE_TARGETS_FILE} DESTINATION ${cmake_dir} ${only})
  export(EXPORT ${I_EXPORT} NAMESPACE pagecache:: FILE ${I_CONFIG_DIR}/${PAGECACHE_TARGETS_FILE})
  configure_package_config_file(cmake/pagecacheConfig.cmake.in ${I_CONFIG_DIR}/pagecacheConfig.cmake
    INSTALL_DESTINATION ${cmake_dir})
  write_basic_package_version_file(${I_CONFIG_DIR}/pagecacheConfigVersion.cmake COMPATIBILITY SameMinorVersion)
  install(FILES ${I_CONFIG_DIR}/pagecacheConfig.cmake ${I_CONFIG_DIR}/pagecacheConfigVersion.cmake
          DESTINATION ${cmake_dir} ${only})

  # pkg-config: paths relative to the .pc file's own folder, so that the prefix may be moved. A
  # static library needs its dependencies on every link line; a shared one links them itself.
  file(RELATIVE_PATH PAGECACHE_PC_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
  string(REGEX REPLACE "/$" "" PAGECACHE_PC_PREFIX "${PAGECACHE_PC_PREFIX}")
  file(RELATIVE_PATH PAGECACHE_PC_LIBDIR ${CMAKE_INSTALL_PREFIX} ${CMAKE_INSTALL_FULL_LIBDIR})
  file(RELATIVE_PATH PAGECACHE_PC_INCLUDEDIR ${CMAKE_INSTALL_PREFIX} ${CMAKE_INSTALL_FULL_INCLUDEDIR})
  set(PAGECACHE_PC_REQUIRES "Requires")
  if(I_SHARED)
    set(PAGECACHE_PC_REQUIRES "Requires.private")
  endif()
  configure_file(cmake/pagecache.pc.in ${I_CONFIG_DIR}/pagecache.pc @ONLY)
  install(FILES ${I_CONFIG_DIR}/pagecache.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig ${only})

  # The command and the data it finds beside itself (cmake/DataDir.cmake); with a shared
  # library, pcsim finds it relative to itself too.
  if(I_PROGRAM)
    if(I_SHARED)
      file(RELATIVE_PATH lib_from_bin ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
      set_target_properties(${I_PROGRAM} PROPERTIES INSTALL_RPATH "$ORIGIN/${lib_from_bin}")
    endif()
    install(TARGETS ${I_PROGRAM} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} ${only})
  endif()
  foreach(folder IN LISTS PCSIM_DATA_FOLDERS)
    install(DIRECTORY ${folder} DESTINATION ${CMAKE_INSTALL_DATADIR}/pcsim ${only})
  endforeach()
  install(FILES LICENSE CITATION.cff README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} ${only})
  install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} ${only})
endfunction()

set(pcsim_program "")
if(TARGET pcsim)
  set(pcsim_program pcsim)
endif()
set(shared_flag "")
if(BUILD_SHARED_LIBS)
  set(shared_flag SHARED)
endif()
pagecache_install(LIBRARY pagecache PROGRAM "${pcsim_program}" EXPORT pagecacheTargets
                  CONFIG_DIR ${PROJECT_BINARY_DIR} ${shared_flag})

# The shared twin: with the tests of a static build, the same objects linked once more as
# libpagecache.so, with a pcsim of its own, so that tests/consumer checks the shared flavour
# without building the project a second time. Built into BINARY_DIR/shared-twin, installed
# only by `cmake --install BUILD --component shared-twin`.
if(PAGECACHE_BUILD_TESTS AND TARGET pcsim AND NOT BUILD_SHARED_LIBS AND NOT PAGECACHE_SANITIZE)
  set(twin ${PROJECT_BINARY_DIR}/shared-twin)
  find_package(tomlplusplus REQUIRED)
  find_package(pugixml REQUIRED)
  find_package(Threads REQUIRED)
  pagecache_library(pagecache_shared_twin SHARED)
  set_target_properties(pagecache_shared_twin PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${twin}/lib)

  add_executable(pcsim_shared_twin $<TARGET_OBJECTS:pcsim_objects> $<TARGET_OBJECTS:pagecache_calibrate>
                 $<TARGET_OBJECTS:pagecache_sweep> $<TARGET_OBJECTS:pagecache_validate>)
  target_link_libraries(pcsim_shared_twin PRIVATE pagecache_shared_twin fmt::fmt tomlplusplus::tomlplusplus Threads::Threads)
  set_target_properties(pcsim_shared_twin PROPERTIES OUTPUT_NAME pcsim RUNTIME_OUTPUT_DIRECTORY ${twin}/bin)
  pagecache_install(LIBRARY pagecache_shared_twin PROGRAM pcsim_shared_twin EXPORT pagecacheSharedTwinTargets
                    CONFIG_DIR ${twin} SHARED COMPONENT shared-twin)
endif()
