# zip_atomically.cmake: a zip file written all or nothing (the kit's and Gradescope's).
#   include(zip_atomically.cmake)
#   zip_atomically(ZIP <final.zip> DIRECTORY <dir> ENTRIES <paths relative to dir...>
#                  RESULT_VARIABLE <var>)
# `cmake -E tar` runs in DIRECTORY and writes a temporary name beside ZIP (".ZIP." and
# random letters, created by nobody else); only when tar succeeded is it renamed over ZIP
# (rename(2): readers see the old zip or the new one, never half of one). On failure the
# temporary file is removed, ZIP is left as it was, and <var> holds the reason; on
# success <var> is empty. `cmake -E tar` itself leaves a partial zip behind when it fails,
# which is why it never writes ZIP directly.
function(zip_atomically)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "ZIP;DIRECTORY;RESULT_VARIABLE" "ENTRIES")
  get_filename_component(folder ${arg_ZIP} DIRECTORY)
  get_filename_component(name ${arg_ZIP} NAME)
  string(RANDOM LENGTH 12 suffix)
  set(partial ${folder}/.${name}.${suffix})
  if(EXISTS ${partial})
    set(${arg_RESULT_VARIABLE} "${partial} exists already" PARENT_SCOPE)
    return()
  endif()
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E tar cf ${partial} --format=zip ${arg_ENTRIES}
    WORKING_DIRECTORY ${arg_DIRECTORY}
    RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    file(REMOVE ${partial})
    set(${arg_RESULT_VARIABLE} "cmake -E tar failed (${status}); ${arg_ZIP} left as it was"
        PARENT_SCOPE)
    return()
  endif()
  file(RENAME ${partial} ${arg_ZIP} RESULT rename_status)
  if(NOT rename_status EQUAL 0)
    file(REMOVE ${partial})
    set(${arg_RESULT_VARIABLE} "renaming ${partial} to ${arg_ZIP}: ${rename_status}"
        PARENT_SCOPE)
    return()
  endif()
  set(${arg_RESULT_VARIABLE} "" PARENT_SCOPE)
endfunction()
