# assignment.cmake: makes one chapter's assignment kit and its zip. Run by the targets
# assignment-chNN (see CMakeLists.txt here) and by the kit tests:
#   cmake -DMAKE_KIT=... -DSOURCE=... -DCHAPTER=NN -DOUTPUT=.../assignments
#         [-DVERSION=...] -P assignment.cmake
# writes OUTPUT/chNN/ (the kit, made by make-kit), OUTPUT/chNN.zip (the kit in a folder
# chNN, for students) and OUTPUT/chNN-gradescope.zip (the kit's files at the root of the
# zip, where Gradescope wants setup.sh and run_autograder). The kit is stamped with
# VERSION and the commit SOURCE is at (source_commit.cmake; "unknown" outside git).
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
# The commit the kit is made from, read now (when the kit is made), not at configure time.
include(${CMAKE_CURRENT_LIST_DIR}/source_commit.cmake)
source_commit(${SOURCE} commit)
execute_process(
  COMMAND ${MAKE_KIT} kit --source ${SOURCE} --template ${CMAKE_CURRENT_LIST_DIR}/template
          --chapter ${CHAPTER} --out ${OUTPUT}/${kit} --version ${VERSION}
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
file(GLOB entries RELATIVE ${OUTPUT}/${kit} ${OUTPUT}/${kit}/*)
list(REMOVE_ITEM entries .exactpixels-kit)
zip_atomically(ZIP ${OUTPUT}/${kit}-gradescope.zip DIRECTORY ${OUTPUT}/${kit}
               ENTRIES ${entries} RESULT_VARIABLE problem)
if(problem)
  message(FATAL_ERROR
          "assignment-${kit}: zipping the Gradescope autograder failed: ${problem}")
endif()
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}-gradescope.zip (Gradescope)")
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}/ and ${OUTPUT}/${kit}.zip")
