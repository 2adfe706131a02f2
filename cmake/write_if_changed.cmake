# write_if_changed(FILE CONTENT): writes CONTENT to FILE only when it differs from what FILE
# holds, so that a generated source rebuilds nothing while it is unchanged (core/build_info.cmake,
# studies/embed_study_files.cmake).
function(write_if_changed file content)
  set(old "")
  if(EXISTS ${file})
    file(READ ${file} old)
  endif()
  if(NOT old STREQUAL content)
    file(WRITE ${file} "${content}")
  endif()
endfunction()
