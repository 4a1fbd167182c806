# pcsim's data (the paper's scenarios, the shipped platforms, the validation data, the inputs
# made by others) is installed under DATADIR/pcsim, and pcsim finds it at PCSIM_DATA_RELATIVE
# from its own folder (apps/pcsim/data_dir.hpp): never a path fixed at build time, so that an
# install prefix may be moved (a .deb, Spack, a copied folder).
#
# The build tree mirrors that layout: pcsim is built into PCSIM_BUILD_BINDIR, and the data
# folder beside it holds links to the source tree's folders, so that a built pcsim finds its
# data as an installed one does.
set(PCSIM_DATA_FOLDERS scenarios platforms inputs validation)
file(RELATIVE_PATH PCSIM_DATA_RELATIVE ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_DATADIR}/pcsim)
set(PCSIM_BUILD_BINDIR ${PROJECT_BINARY_DIR}/bin)
get_filename_component(pcsim_build_data ${PCSIM_BUILD_BINDIR}/${PCSIM_DATA_RELATIVE} ABSOLUTE)
file(MAKE_DIRECTORY ${pcsim_build_data})
foreach(folder IN LISTS PCSIM_DATA_FOLDERS)
  if(NOT EXISTS ${pcsim_build_data}/${folder})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${pcsim_build_data}/${folder} SYMBOLIC)
  endif()
endforeach()
