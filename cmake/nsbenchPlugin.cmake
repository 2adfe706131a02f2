# nsbench_add_plugin(<target> [SOURCES] <source>...)
# Builds a loadable module (<target>.so, no "lib" prefix) that registers integrators and/or
# problems with NSBENCH_INTEGRATOR / NSBENCH_PROBLEM; load it with
#   nsbench --plugin <target>.so ...   or   NSBENCH_PLUGINS=<target>.so nsbench ...
# Optimised unless told otherwise: with no CMAKE_BUILD_TYPE (CMake's default, which passes no
# -O flag at all, so -O0) the plugin is compiled with the Release flags, since its CPU times
# are measured beside nsbench's own Release code. Any build type given (Debug, ...) is kept.
# The build type and the flags are compiled into the plugin (core/plugin.hpp), and the
# reports print them beside its hash; nsbench warns on a run with an unoptimised plugin.
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

  get_property(multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
  if(multi_config)
    set(build_type "$<CONFIG>")
    set(config_flags "")
  elseif(CMAKE_BUILD_TYPE)
    set(build_type "${CMAKE_BUILD_TYPE}")
    string(TOUPPER "${CMAKE_BUILD_TYPE}" config)
    set(config_flags "${CMAKE_CXX_FLAGS_${config}}")
  else()
    set(build_type "Release (nsbench_add_plugin's default: no CMAKE_BUILD_TYPE)")
    separate_arguments(release_flags NATIVE_COMMAND "${CMAKE_CXX_FLAGS_RELEASE}")
    target_compile_options(${target} PRIVATE ${release_flags})
    set(config_flags "")
  endif()
  # The flags as the compiler gets them, in order: CMAKE_CXX_FLAGS, the build type's, then the
  # target's options (read when the build system is generated: options added after this call
  # are included).
  set(flags "${CMAKE_CXX_FLAGS} ${config_flags} $<JOIN:$<TARGET_PROPERTY:${target},COMPILE_OPTIONS>, >")
  string(REGEX REPLACE "  +" " " flags "${flags}")
  string(STRIP "${flags}" flags)
  target_compile_definitions(${target} PRIVATE "NSBENCH_PLUGIN_BUILD_TYPE=\"${build_type}\""
                                               "NSBENCH_PLUGIN_COMPILE_FLAGS=\"${flags}\"")
endfunction()
