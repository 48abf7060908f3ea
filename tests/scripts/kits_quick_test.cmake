# kits_quick_test.cmake: the quick check of the assignment kits that the test workflow
# runs (CTest `kits_quick`, label `kits`); the full check, every kit built, graded fresh
# and restored, is the `assignments` test of the course workflow.
#   cmake -DMAKE_KIT=... -DKIT_SCRIPT=.../assignment.cmake -DSOURCE=... -DCHAPTERS="00;01;..."
#         -DBUILT=02 -DWORK=... -DCXX=... -DGENERATOR=... -P kits_quick_test.cmake
# 1. Every chapter's kit is made (kit folder, student zip, Gradescope zip), as the
#    assignment-chNN targets make it.
# 2. Chapter BUILT's kit configures and builds on its own, outside the source tree, and
#    fresh its grade fails exactly the tests of its exercises (at least one), passes every
#    other test, and every exercise region of the kit is checked by a failing test.
cmake_minimum_required(VERSION 3.25)
foreach(required MAKE_KIT KIT_SCRIPT SOURCE CHAPTERS BUILT WORK CXX GENERATOR)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "kits_quick_test.cmake: -D${required}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
set(out ${WORK}/assignments)

foreach(number IN LISTS CHAPTERS)
  execute_process(COMMAND ${CMAKE_COMMAND} -DMAKE_KIT=${MAKE_KIT} -DSOURCE=${SOURCE}
                          -DCHAPTER=${number} -DOUTPUT=${out} -P ${KIT_SCRIPT}
                  RESULT_VARIABLE status OUTPUT_VARIABLE log ERROR_VARIABLE log)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "the chapter ${number} kit could not be made:\n${log}")
  endif()
  foreach(made ch${number}/CMakeLists.txt ch${number}.zip ch${number}-gradescope.zip)
    if(NOT EXISTS ${out}/${made})
      message(FATAL_ERROR "making the chapter ${number} kit left no ${out}/${made}")
    endif()
  endforeach()
endforeach()
list(LENGTH CHAPTERS made_count)
message(STATUS "made ${made_count} kits: ${CHAPTERS}")

set(kit ${out}/ch${BUILT})
set(build ${WORK}/build-ch${BUILT})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${kit} -B ${build} -G ${GENERATOR}
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX}
                RESULT_VARIABLE status OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the chapter ${BUILT} kit does not configure on its own:\n${log}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${build} -j2
                RESULT_VARIABLE status OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the chapter ${BUILT} kit does not build on its own:\n${log}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${build} --target grade
                RESULT_VARIABLE status OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT status EQUAL 0 OR NOT EXISTS ${build}/grade.txt)
  message(FATAL_ERROR "grading the fresh chapter ${BUILT} kit failed:\n${log}")
endif()

# The kit's exercise regions: "// EXERCISE chNN-id: hint" in its code.
file(GLOB_RECURSE code ${kit}/*.cpp ${kit}/*.hpp ${kit}/*.h)
set(exercises)
foreach(file IN LISTS code)
  file(STRINGS ${file} begins REGEX "^[ \t]*// EXERCISE ch[0-9][0-9]-[a-z0-9-]+: ")
  foreach(line IN LISTS begins)
    string(REGEX REPLACE "^[ \t]*// EXERCISE (ch[0-9][0-9]-[a-z0-9-]+): .*$" "\\1" id
           "${line}")
    list(APPEND exercises ${id})
  endforeach()
endforeach()
list(REMOVE_DUPLICATES exercises)
if(NOT exercises)
  message(FATAL_ERROR "the chapter ${BUILT} kit has no exercise region: pick a chapter "
                      "that has one for -DBUILT")
endif()

# Grade lines: STATUS EARNED/DECLARED EXERCISE NAME ("-" for no exercise).
file(STRINGS ${build}/grade.txt lines REGEX "^(PASS|FAIL|SKIP) [0-9]+/[0-9]+ ")
set(problems)
set(failing)
foreach(line IN LISTS lines)
  string(REGEX MATCH "^([A-Z]+) [0-9]+/[0-9]+ ([^ ]+) " _ "${line}")
  set(state ${CMAKE_MATCH_1})
  set(exercise ${CMAKE_MATCH_2})
  if(exercise STREQUAL "-")
    if(state STREQUAL "FAIL")
      list(APPEND problems "a test of no exercise fails in the fresh kit: ${line}")
    endif()
  elseif(NOT state STREQUAL "FAIL")
    list(APPEND problems "an exercise's test does not fail in the fresh kit: ${line}")
  else()
    list(APPEND failing ${exercise})
  endif()
endforeach()
foreach(exercise IN LISTS exercises)
  if(NOT exercise IN_LIST failing)
    list(APPEND problems "exercise ${exercise} is checked by no failing test")
  endif()
endforeach()
if(problems)
  file(READ ${build}/grade.txt grade)
  list(JOIN problems "\n" problems)
  message(FATAL_ERROR "${problems}\nthe grade:\n${grade}")
endif()
list(LENGTH lines case_count)
message(STATUS "the fresh chapter ${BUILT} kit: ${case_count} test cases, the tests of "
               "${exercises} fail and no other")
file(REMOVE_RECURSE ${WORK})
