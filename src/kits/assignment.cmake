# assignment.cmake: makes one chapter's assignment kit and its zip. Run by the targets
# assignment-chNN (see CMakeLists.txt here) and by the kit tests:
#   cmake -DMAKE_KIT=... -DSOURCE=... -DCHAPTER=NN -DOUTPUT=.../assignments
#         [-DVERSION=...] [-DGRADE_RUNNER=... -DTIMING_PROGRAM=...] -P assignment.cmake
# writes OUTPUT/chNN/ (the kit, made by make-kit), OUTPUT/chNN.zip (the kit in a folder
# chNN, for students) and OUTPUT/chNN-gradescope.zip (the kit's files at the root of the
# zip, where Gradescope wants setup.sh and run_autograder, plus the teacher's hidden tests
# SOURCE/tests/hidden/chNN_*.cpp, which the students' kit never holds). The kit is stamped
# with VERSION and the commit SOURCE is at (source_commit.cmake; "unknown" outside git).
#
# With TIMING_PROGRAM (the chapter's test program built from the book's code, which is
# the kit with its solutions restored), GRADE_RUNNER --measure times each of its test
# cases and the kit gets time_limits.txt: each test case's limit and a budget for all
# (the rule is in grade_runner.cpp, limit_multiple).
foreach(required MAKE_KIT SOURCE CHAPTER OUTPUT)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "assignment.cmake: -D${required}=... is required")
  endif()
endforeach()
if(NOT DEFINED VERSION)
  set(VERSION 0.0.0)
endif()
set(kit ch${CHAPTER})
file(MAKE_DIRECTORY ${OUTPUT})
set(limits_option)
if(DEFINED TIMING_PROGRAM)
  if(NOT DEFINED GRADE_RUNNER)
    message(FATAL_ERROR "assignment.cmake: -DTIMING_PROGRAM wants -DGRADE_RUNNER=... too")
  endif()
  execute_process(
    COMMAND ${GRADE_RUNNER} --tests ${TIMING_PROGRAM}
            --measure ${OUTPUT}/${kit}-time_limits.txt
    RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "assignment-${kit}: timing the solution's test cases failed")
  endif()
  set(limits_option --time-limits ${OUTPUT}/${kit}-time_limits.txt)
endif()
# The commit the kit is made from, read now (when the kit is made), not at configure time.
include(${CMAKE_CURRENT_LIST_DIR}/source_commit.cmake)
source_commit(${SOURCE} commit)
execute_process(
  COMMAND ${MAKE_KIT} kit --source ${SOURCE} --template ${CMAKE_CURRENT_LIST_DIR}/template
          --chapter ${CHAPTER} --out ${OUTPUT}/${kit} --version ${VERSION} ${limits_option}
          --commit ${commit}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "assignment-${kit}: make-kit failed (see above)")
endif()
# Both zips are written to a temporary name and renamed into place only when tar
# succeeded (zip_atomically.cmake): a failure leaves the previous zip, never half of one.
include(${CMAKE_CURRENT_LIST_DIR}/zip_atomically.cmake)
zip_atomically(ZIP ${OUTPUT}/${kit}.zip DIRECTORY ${OUTPUT} ENTRIES ${kit}
               RESULT_VARIABLE problem)
if(problem)
  message(FATAL_ERROR "assignment-${kit}: zipping ${kit} failed: ${problem}")
endif()
# The autograder: the kit and the hidden tests, gathered in OUTPUT/chNN-autograder/.
set(autograder ${OUTPUT}/${kit}-autograder)
file(REMOVE_RECURSE ${autograder})
file(COPY ${OUTPUT}/${kit}/ DESTINATION ${autograder} PATTERN .exactpixels-kit EXCLUDE)
file(GLOB hidden ${SOURCE}/tests/hidden/${kit}_*.cpp)
if(hidden)
  file(COPY ${hidden} DESTINATION ${autograder}/tests/hidden)
endif()
file(GLOB entries RELATIVE ${autograder} ${autograder}/*)
zip_atomically(ZIP ${OUTPUT}/${kit}-gradescope.zip DIRECTORY ${autograder}
               ENTRIES ${entries} RESULT_VARIABLE problem)
if(problem)
  message(FATAL_ERROR
          "assignment-${kit}: zipping the Gradescope autograder failed: ${problem}")
endif()
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}-gradescope.zip (Gradescope)")
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}/ and ${OUTPUT}/${kit}.zip")
