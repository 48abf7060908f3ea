# assignment.cmake: makes one chapter's assignment kit and its zip. Run by the targets
# assignment-chNN (see CMakeLists.txt here) and by the kit tests:
#   cmake -DMAKE_KIT=... -DSOURCE=... -DCHAPTER=NN -DOUTPUT=.../assignments
#         [-DVERSION=...] -P assignment.cmake
# writes OUTPUT/chNN/ (the kit, made by make-kit) and OUTPUT/chNN.zip.
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
message(STATUS "assignment-${kit}: ${OUTPUT}/${kit}/ and ${OUTPUT}/${kit}.zip")
