# Writes build_info.cpp only when its content changes, so a rebuild relinks only when
# the revision or the configuration did.
execute_process(COMMAND git -C ${SOURCE_DIR} rev-parse --short=12 HEAD
                OUTPUT_VARIABLE REV OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR REV STREQUAL "")
  set(REV "unknown")
else()
  # Dirty: a tracked file that builds the binaries differs from HEAD. The reports, the docs and
  # other prose build nothing: the main command rewrites reports/, and a build after it is not
  # "-dirty" for that (scripts/report_revisions.py counts the same files as code, and more).
  execute_process(COMMAND git -C ${SOURCE_DIR} status --porcelain --untracked-files=no -- .
                          ":(exclude)reports" ":(exclude)docs" ":(exclude)*.md" ":(exclude)CITATION.cff"
                  OUTPUT_VARIABLE DIRTY OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT DIRTY STREQUAL "")
    set(REV "${REV}-dirty")
  endif()
endif()
if(SANITIZE)
  set(BUILD_TYPE "${BUILD_TYPE}+asan+ubsan")
endif()
if(NATIVE)
  set(BUILD_TYPE "${BUILD_TYPE}+native")
endif()
set(CONTENT "#include \"core/build_info.hpp\"
namespace nsb {
const BuildInfo& build_info() {
  static const BuildInfo info{\"${VERSION}\", \"${REV}\", \"${BUILD_TYPE}\", \"${COMPILER}\"};
  return info;
}
}  // namespace nsb
")
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/write_if_changed.cmake)
write_if_changed(${OUTPUT} "${CONTENT}")
