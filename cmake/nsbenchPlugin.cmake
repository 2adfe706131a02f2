# nsbench_add_plugin(<target> [SOURCES] <source>...)
# Builds a loadable module (<target>.so, no "lib" prefix) that registers integrators and/or
# problems with NSBENCH_INTEGRATOR / NSBENCH_PROBLEM; load it with
#   nsbench --plugin <target>.so ...   or   NSBENCH_PLUGINS=<target>.so nsbench ...
function(nsbench_add_plugin target)
  set(sources ${ARGN})
  list(REMOVE_ITEM sources SOURCES)
  if(NOT sources)
    message(FATAL_ERROR "nsbench_add_plugin(${target}): no sources")
  endif()
  add_library(${target} MODULE ${sources})
  target_link_libraries(${target} PRIVATE nsbench::nsbench)
  target_compile_features(${target} PRIVATE cxx_std_20)
  target_compile_definitions(${target} PRIVATE NSBENCH_PLUGIN)  # exports the marker (core/plugin.hpp)
  set_target_properties(${target} PROPERTIES PREFIX "" CXX_EXTENSIONS OFF)
endfunction()
