# Writes build_info.cpp only when its content changes, so a rebuild relinks only when
# the revision or the configuration did.
set(DIRTY_FILES "")
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
    # What differed, for a run to say (porcelain lines "XY path"): the first 8 paths, then a count.
    string(REPLACE "\n" ";" _lines "${DIRTY}")
    list(LENGTH _lines _count)
    set(_paths "")
    foreach(_line IN LISTS _lines)
      string(SUBSTRING "${_line}" 3 -1 _path)
      list(APPEND _paths "${_path}")
    endforeach()
    if(_count GREATER 8)
      list(SUBLIST _paths 0 8 _paths)
    endif()
    list(JOIN _paths ", " DIRTY_FILES)
    if(_count GREATER 8)
      math(EXPR _more "${_count} - 8")
      string(APPEND DIRTY_FILES " and ${_more} more")
    endif()
    string(REPLACE "\\" "\\\\" DIRTY_FILES "${DIRTY_FILES}")
    string(REPLACE "\"" "\\\"" DIRTY_FILES "${DIRTY_FILES}")
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
  static const BuildInfo info{\"${VERSION}\", \"${REV}\", \"${BUILD_TYPE}\", \"${COMPILER}\", \"${DIRTY_FILES}\"};
  return info;
}
}  // namespace nsb
")
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/write_if_changed.cmake)
write_if_changed(${OUTPUT} "${CONTENT}")
