# assignment.cmake: makes one chapter's assignment kit and its zip. Run by the targets
# assignment-chNN (see CMakeLists.txt here) and by the kit tests:
#   cmake -DMAKE_KIT=... -DSOURCE=... -DCHAPTER=NN -DOUTPUT=.../assignments
#         [-DVERSION=...] -P assignment.cmake
# writes OUTPUT/chNN/ (the kit, made by make-kit), OUTPUT/chNN.zip (the kit in a folder
# chNN, for students) and OUTPUT/chNN-gradescope.zip (the kit's files at the root of the
# zip, where Gradescope wants setup.sh and run_autograder).
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
execute_process(
  COMMAND ${MAKE_KIT} kit --source ${SOURCE} --template ${CMAKE_CURRENT_LIST_DIR}/template
          --chapter ${CHAPTER} --out ${OUTPUT}/${kit} --version ${VERSION}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "assignment-${kit}: make-kit failed (see above)")
endif()
file(REMOVE ${OUTPUT}/${kit}.zip)
execute_process(
  COMMAND ${CMAKE_COMMAND} -E tar cf ${kit}.zip --format=zip ${kit}
  WORKING_DIRECTORY ${OUTPUT}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "assignment-${kit}: zipping ${kit} failed")
endif()
file(REMOVE ${OUTPUT}/${kit}-gradescope.zip)
file(GLOB entries RELATIVE ${OUTPUT}/${kit} ${OUTPUT}/${kit}/*)
list(REMOVE_ITEM entries .exactpixels-kit)
execute_process(
  COMMAND ${CMAKE_COMMAND} -E tar cf ../${kit}-gradescope.zip --format=zip ${entries}
  WORKING_DIRECTORY ${OUTPUT}/${kit}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "assignment-${kit}: zipping the Gradescope autograder failed")
endif()
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}-gradescope.zip (Gradescope)")
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}/ and ${OUTPUT}/${kit}.zip")
