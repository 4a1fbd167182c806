# The source tree is layered: engine <- storage <- cache <- workload <- scenario/report <- apps,
# with text (the outputs' escaping) below the layers that write text.
# Each layer's target sees, as include root, a folder of the build tree that holds links to its
# own sources and to the layers below it only; an include of a higher layer fails to compile.
#
#   pagecache_layer(NAME storage BELOW engine)
#
# creates ${PAGECACHE_LAYER_ROOT}/storage/{engine,storage} -> src/{engine,storage}. A layer may be
# a folder of a room (formats/fio): its link keeps the path, its target replaces '/' by '_'.
set(PAGECACHE_LAYER_ROOT ${CMAKE_BINARY_DIR}/layers)

function(pagecache_layer_include_root name out_var)
  set(${out_var} ${PAGECACHE_LAYER_ROOT}/${name} PARENT_SCOPE)
endfunction()

function(pagecache_layer)
  cmake_parse_arguments(L "" "NAME" "BELOW" ${ARGN})
  set(root ${PAGECACHE_LAYER_ROOT}/${L_NAME})
  file(MAKE_DIRECTORY ${root})
  foreach(visible IN LISTS L_BELOW L_NAME)
    if(NOT EXISTS ${root}/${visible})
      get_filename_component(parent ${root}/${visible} DIRECTORY)
      file(MAKE_DIRECTORY ${parent})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/src/${visible} ${root}/${visible} SYMBOLIC)
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY PAGECACHE_LAYER_${L_NAME}_VISIBLE "${L_BELOW};${L_NAME}")
endfunction()
