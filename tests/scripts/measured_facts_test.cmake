# A test program run with --facts=FILE writes the values its tests recorded
# (tests/support/measured_facts.hpp) all or nothing: run by CTest as
#   cmake -DTESTS=<test_ch05> -DWORK=<folder> -P this file
# After a passing run FILE holds one "NAME VALUE" line per fact; a FILE that cannot be
# written is an error naming it (exit code 2), and a run that only lists the tests
# writes nothing. EMULATOR (a list, optional) runs the program in a cross build.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(selection "--test-case=the grazing floor spans*")
execute_process(COMMAND ${EMULATOR} ${TESTS} ${selection} --facts=${WORK}/facts.txt
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK}/facts.txt)
  message(FATAL_ERROR "${TESTS} wrote no facts after a passing run (${status})")
endif()
file(STRINGS ${WORK}/facts.txt lines REGEX "^ch05_floor_ratio_(low|high) ")
list(LENGTH lines count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "facts.txt lacks the floor's two ratios: '${lines}'")
endif()
foreach(line IN LISTS lines)
  # The values are the ones the test asserted: low in [1.1, 1.2], high in [20, 21].
  string(REGEX MATCH "^ch05_floor_ratio_(low|high) ([0-9.]+)$" matched "${line}")
  if(NOT matched)
    message(FATAL_ERROR "not a NAME VALUE line: '${line}'")
  endif()
  set(value ${CMAKE_MATCH_2})
  if(CMAKE_MATCH_1 STREQUAL "low" AND (value LESS 1.1 OR value GREATER 1.2))
    message(FATAL_ERROR "low ratio ${value} is not the tested one")
  elseif(CMAKE_MATCH_1 STREQUAL "high" AND (value LESS 20 OR value GREATER 21))
    message(FATAL_ERROR "high ratio ${value} is not the tested one")
  endif()
endforeach()
execute_process(COMMAND ${EMULATOR} ${TESTS} ${selection} --facts=${WORK}/missing/facts.txt
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE message)
if(NOT status EQUAL 2)
  message(FATAL_ERROR "an unwritable facts file exited ${status}, not 2")
endif()
if(NOT message MATCHES "missing/facts.txt: cannot write")
  message(FATAL_ERROR "the message does not name the facts file: ${message}")
endif()
if(EXISTS ${WORK}/missing)
  message(FATAL_ERROR "${TESTS} created ${WORK}/missing")
endif()
execute_process(COMMAND ${EMULATOR} ${TESTS} --list-test-cases --facts=${WORK}/listed.txt
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
if(EXISTS ${WORK}/listed.txt)
  message(FATAL_ERROR "listing the tests wrote a facts file")
endif()
message(STATUS "${TESTS}: facts written after a passing run, refused loudly otherwise")
