# source_commit.cmake: source_commit(DIR OUT) sets OUT to the commit the source tree at
# DIR was made from, as git says at build time: the first 12 hex digits of HEAD, with
# "+changes" when a tracked file differs from that commit; "unknown" when DIR is not a
# git checkout (a tarball, an unpacked zip) or git is not installed. Used by the kits
# (assignment.cmake: the kit's README and its grader say it) and the book's title page
# (book/render.cmake); tests/scripts/source_commit_test.cmake checks it.
function(source_commit dir out)
  set(commit unknown)
  find_program(SOURCE_COMMIT_GIT git)
  # DIR itself must be the checkout (.git is a folder, or a file in a worktree): a tarball
  # unpacked inside some other repository must not take that repository's commit.
  if(SOURCE_COMMIT_GIT AND EXISTS ${dir}/.git)
    execute_process(COMMAND ${SOURCE_COMMIT_GIT} -C ${dir} rev-parse --short=12 HEAD
                    RESULT_VARIABLE result OUTPUT_VARIABLE hash ERROR_QUIET
                    OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(result EQUAL 0 AND hash MATCHES "^[0-9a-f]+$")
      set(commit ${hash})
      execute_process(COMMAND ${SOURCE_COMMIT_GIT} -C ${dir} status --porcelain
                              --untracked-files=no
                      RESULT_VARIABLE result OUTPUT_VARIABLE changes ERROR_QUIET)
      if(NOT result EQUAL 0 OR NOT changes STREQUAL "")
        string(APPEND commit "+changes")
      endif()
    endif()
  endif()
  set(${out} ${commit} PARENT_SCOPE)
endfunction()
