# A kit says which sources it came from (src/kits/source_commit.cmake, assignment.cmake):
# run by CTest as
#   cmake -DROOT=<source tree> -DKITS=src/kits -DMAKE_KIT=<make-kit> -DWORK=<folder> -P this
# - ROOT's commit is git's HEAD (12 hex digits, "+changes" when tracked files differ);
# - a folder that is no checkout says "unknown", even inside one (a tarball unpacked in a
#   clone must not take the clone's commit);
# - a kit made from the fixture tree without .git is stamped "unknown", and once the tree
#   is committed to git, with that commit, in its README and in its grader's definition.
include(${KITS}/source_commit.cmake)
find_program(GIT git REQUIRED)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect what actual expected)
  if(NOT actual STREQUAL expected)
    message(FATAL_ERROR "${what}: '${actual}', expected '${expected}'")
  endif()
endfunction()
function(expect_in what file text)
  file(READ ${file} content)
  string(FIND "${content}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${what}: ${file} does not say '${text}'")
  endif()
endfunction()

# The book's own tree.
source_commit(${ROOT} commit)
if(EXISTS ${ROOT}/.git)
  execute_process(COMMAND ${GIT} -C ${ROOT} rev-parse HEAD OUTPUT_VARIABLE head
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  string(SUBSTRING "${head}" 0 12 head)
  if(NOT commit MATCHES "^${head}(\\+changes)?$")
    message(FATAL_ERROR "the source tree's commit: '${commit}', HEAD is ${head}")
  endif()
else()
  expect("a source tree without .git" "${commit}" unknown)
endif()

# A tarball unpacked inside a clone (WORK is in the build folder, often inside one).
file(MAKE_DIRECTORY ${WORK}/unpacked)
source_commit(${WORK}/unpacked commit)
expect("a folder that is no checkout" "${commit}" unknown)

# A kit made from a tree without .git, then from the same tree committed.
set(tree ${WORK}/tree)
file(COPY ${ROOT}/tests/fixtures/kits/tree/ DESTINATION ${tree})
file(COPY ${ROOT}/tests/support DESTINATION ${tree}/tests)
function(make_kit out)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -DMAKE_KIT=${MAKE_KIT} -DSOURCE=${tree} -DCHAPTER=07
            -DOUTPUT=${out} -DVERSION=9.8.7 -P ${KITS}/assignment.cmake
    RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "making the fixture kit failed:\n${output}")
  endif()
endfunction()
make_kit(${WORK}/plain)
expect_in("the kit of a tarball" ${WORK}/plain/ch07/README.md
  "Kit version 9.8.7, made from commit `unknown`")
expect_in("the grader of a tarball's kit" ${WORK}/plain/ch07/CMakeLists.txt
  "EXACTPIXELS_KIT_STAMP=\"chapter 07 kit, version 9.8.7, commit unknown\"")

set(git_env ${CMAKE_COMMAND} -E env GIT_AUTHOR_NAME=kit GIT_AUTHOR_EMAIL=kit@example.org
    GIT_COMMITTER_NAME=kit GIT_COMMITTER_EMAIL=kit@example.org)
foreach(step "init -q" "add -A" "commit -q -m fixture")
  separate_arguments(words UNIX_COMMAND "${step}")
  execute_process(COMMAND ${git_env} ${GIT} -C ${tree} ${words} RESULT_VARIABLE status
                  ERROR_VARIABLE error)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "git ${step} in ${tree}: ${error}")
  endif()
endforeach()
execute_process(COMMAND ${GIT} -C ${tree} rev-parse --short=12 HEAD
                OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE)
make_kit(${WORK}/committed)
expect_in("the kit of a commit" ${WORK}/committed/ch07/README.md
  "Kit version 9.8.7, made from commit `${head}`")
expect_in("the grader of a commit's kit" ${WORK}/committed/ch07/CMakeLists.txt
  "commit ${head}\"")
# A change to a tracked file shows.
file(APPEND ${tree}/src/CMakeLists.txt "# changed\n")
source_commit(${tree} commit)
expect("a tree with a changed file" "${commit}" "${head}+changes")
message(STATUS "kit stamps: unknown without git, ${head} from git, ${head}+changes")
