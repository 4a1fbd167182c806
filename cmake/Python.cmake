# The Python module `pcsim` (python/): built when Python's headers and pybind11 are there
# (Debian: python3-dev, pybind11-dev), unless PAGECACHE_BUILD_PYTHON is OFF. The library is then
# compiled position-independent, to be linked into the module.
option(PAGECACHE_BUILD_PYTHON "Build the Python module pcsim when Python's headers and pybind11 are found" ON)
set(PAGECACHE_PYTHON OFF)
if(PAGECACHE_BUILD_PYTHON AND NOT PAGECACHE_FUZZ)
  # Debian's python3 is the one its python3-* packages serve; a pyenv or venv interpreter first
  # on PATH would lack them. -DPython3_EXECUTABLE=... (pip install does) chooses another.
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 3.9 COMPONENTS Interpreter Development.Module QUIET)
  if(Python3_FOUND)
    set(PYBIND11_FINDPYTHON ON)
    find_package(pybind11 2.6 CONFIG QUIET)
  endif()
  if(Python3_FOUND AND pybind11_FOUND)
    set(PAGECACHE_PYTHON ON)
    set(CMAKE_POSITION_INDEPENDENT_CODE ON)
    message(STATUS "pcsim: the Python module is built for ${Python3_EXECUTABLE} (${Python3_VERSION})")
  else()
    message(STATUS "pcsim: the Python module is not built (needs python3-dev and pybind11-dev)")
  endif()
endif()
