# lane_symbols_test.cmake: the objects of one instruction set's vector kernels
# (fast/exact_lanes.inl compiled for SET) define no symbol that another object could
# share: every global symbol lies in exactpixels::simd_SET. An inline function or template
# (std:: ones too) instantiated there would be a weak symbol the linker may keep for every
# caller, so that a CPU without SET stops on an illegal instruction (CTest
# `one_definition_lanes_SET`).
#   cmake -DNM=nm -DOBJECTS="a.o|b.o" -DNAMESPACE=exactpixels::simd_avx2:: -P ...
cmake_minimum_required(VERSION 3.25)
foreach(required NM OBJECTS NAMESPACE)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "lane_symbols_test.cmake: -D${required}=... is required")
  endif()
endforeach()
string(REPLACE "|" ";" objects "${OBJECTS}")
set(defined 0)
set(strays)
foreach(object IN LISTS objects)
  execute_process(COMMAND ${NM} -C --defined-only ${object}
    OUTPUT_VARIABLE listing RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${object}")
  endif()
  string(REPLACE "\n" ";" lines "${listing}")
  foreach(line IN LISTS lines)
    # "ADDRESS TYPE NAME": upper-case types (and u, unique global) are global symbols.
    if(line MATCHES "^[0-9a-fA-F]* ([A-Zu]) (.*)$")
      set(name "${CMAKE_MATCH_2}")
      string(FIND "${name}" "${NAMESPACE}" at)
      if(at EQUAL 0)
        math(EXPR defined "${defined} + 1")
      else()
        list(APPEND strays "${CMAKE_MATCH_1} ${name}")
      endif()
    endif()
  endforeach()
endforeach()
if(strays)
  list(JOIN strays "\n  " shown)
  message(FATAL_ERROR "symbols outside ${NAMESPACE} in ${OBJECTS}:\n  ${shown}")
endif()
if(defined LESS 2)
  message(FATAL_ERROR "only ${defined} symbols in ${NAMESPACE}: the kernels are missing")
endif()
message("${defined} global symbols, all in ${NAMESPACE}")
