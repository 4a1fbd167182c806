# `cpack -G DEB` in the build tree makes pcsim_VERSION_ARCH.deb: what `cmake --install` installs,
# under /usr, its dependencies on Debian's libraries found by dpkg-shlibdeps (package dpkg-dev).
# tests/package/deb_test.sh installs it, runs it from another folder and removes it.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pcsim)
set(CPACK_PACKAGE_VENDOR "The pcsim developers")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "pcsim simulates how the Linux page cache shapes the I/O time of data-intensive applications \
(pipelines, workflows, NFS, memory limits). It holds the pcsim command, the pagecache C++20 library \
with its headers, CMake package and pkg-config file, and pcsim's scenarios, platforms and validation data.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "The pcsim developers")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
include(CPack)
