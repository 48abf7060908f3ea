# same_pictures_test.cmake: every scene shipped with chapter 7, rendered by this build's
# exactpixels and by a reference build's (another compiler, CPU or architecture), must
# give the same PNG file byte for byte (CTest `same_pictures`, in the clang, native and
# arm64 presets, whose reference is the default preset's build/bin/exactpixels).
#   cmake -DREFERENCE=.../build/bin/exactpixels -DCANDIDATE=.../exactpixels
#         [-DEMULATOR="qemu-aarch64;-L;/usr/aarch64-linux-gnu"] -DSCENES=... -DWORK=...
#         -P same_pictures_test.cmake
cmake_minimum_required(VERSION 3.25)
foreach(required REFERENCE CANDIDATE SCENES WORK)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "same_pictures_test.cmake: -D${required}=... is required")
  endif()
endforeach()
if(NOT EXISTS ${REFERENCE})
  # SKIP_REGULAR_EXPRESSION of the test matches this line.
  message("SKIPPED: no reference renderer ${REFERENCE}; build the default preset first "
          "(cmake --workflow --preset test) to compare this build's pictures with it")
  return()
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/reference ${WORK}/candidate)
file(GLOB scenes ${SCENES}/*.toml)
if(NOT scenes)
  message(FATAL_ERROR "no scene in ${SCENES}")
endif()
set(different)
foreach(scene IN LISTS scenes)
  get_filename_component(name ${scene} NAME_WE)
  foreach(side reference candidate)
    if(side STREQUAL reference)
      set(command ${REFERENCE})
    else()
      set(command ${EMULATOR} ${CANDIDATE})
    endif()
    execute_process(COMMAND ${command} render ${scene} -o ${WORK}/${side}/${name}.png
                    RESULT_VARIABLE status OUTPUT_VARIABLE log ERROR_VARIABLE log)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "the ${side} renderer failed on ${scene}:\n${log}")
    endif()
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/reference/${name}.png
                          ${WORK}/candidate/${name}.png RESULT_VARIABLE status)
  if(status EQUAL 0)
    message(STATUS "${name}: the same bytes")
  else()
    message(STATUS "${name}: DIFFERENT (${WORK}/reference/${name}.png and "
                   "${WORK}/candidate/${name}.png kept)")
    list(APPEND different ${name})
  endif()
endforeach()
list(LENGTH scenes count)
if(different)
  message(FATAL_ERROR "pictures that differ from the reference build's: ${different}")
endif()
message(STATUS "all ${count} shipped scenes: the same PNG bytes as ${REFERENCE}")
file(REMOVE_RECURSE ${WORK})
