# references.cmake: every reference to the book in the code (comments in src/, tests/,
# figures/, bench/ and the chapter examples) names a label the book defines:
# @eq:name, @sec:name, @fig:name, @tbl:name or @lst:name, as the chapters write them. A
# number such as "eq. 2.8" is refused: numbers move when a chapter gains an equation,
# labels do not. Run as the `references` test (label `layers`):
#   cmake -DSOURCE=. -P src/checks/references.cmake
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED SOURCE)
  message(FATAL_ERROR "usage: cmake -DSOURCE=DIR -P references.cmake")
endif()
get_filename_component(SOURCE "${SOURCE}" ABSOLUTE)

# The labels the book defines: {#eq:x}, {#fig:x}, {#tbl:x}, {#lst:x} and sections
# {#sec:x}, in the chapters and the other book pages; listings named #lst:x inside
# snippet braces count too.
file(GLOB pages ${SOURCE}/chapters/*/chapter.md ${SOURCE}/book/*.md)
set(defined)
foreach(page IN LISTS pages)
  file(READ ${page} text)
  string(REGEX MATCHALL "#(eq|sec|fig|tbl|lst):[A-Za-z0-9_-]+" found "${text}")
  foreach(label IN LISTS found)
    string(SUBSTRING "${label}" 1 -1 label)
    list(APPEND defined "${label}")
  endforeach()
endforeach()
list(REMOVE_DUPLICATES defined)

file(GLOB_RECURSE code
  ${SOURCE}/src/*.hpp ${SOURCE}/src/*.cpp ${SOURCE}/tests/*.hpp ${SOURCE}/tests/*.cpp
  ${SOURCE}/figures/*.cpp ${SOURCE}/bench/*.cpp ${SOURCE}/chapters/*.cpp)
set(errors 0)
set(checked 0)
foreach(file IN LISTS code)
  file(RELATIVE_PATH rel ${SOURCE} ${file})
  # The book filter's own tests hold made-up chapters with made-up labels.
  if(rel MATCHES "^tests/(fixtures/|book_|bookcheck_)")
    continue()
  endif()
  file(STRINGS ${file} lines REGEX "@(eq|sec|fig|tbl|lst):|[Ee]qs?\\. ?[0-9]+\\.[0-9]")
  foreach(line IN LISTS lines)
    if(line MATCHES "[Ee]qs?\\. ?[0-9]+\\.[0-9]+")
      message(SEND_ERROR "${rel}: '${CMAKE_MATCH_0}': refer to an equation by its label "
                         "(@eq:name), not by its number")
      math(EXPR errors "${errors} + 1")
    endif()
    string(REGEX MATCHALL "@(eq|sec|fig|tbl|lst):[A-Za-z0-9_-]*[A-Za-z0-9]" refs "${line}")
    foreach(ref IN LISTS refs)
      string(SUBSTRING "${ref}" 1 -1 label)
      math(EXPR checked "${checked} + 1")
      if(NOT label IN_LIST defined)
        message(SEND_ERROR "${rel}: '@${label}' is not a label of any chapter or book page")
        math(EXPR errors "${errors} + 1")
      endif()
    endforeach()
  endforeach()
endforeach()
if(errors GREATER 0)
  message(FATAL_ERROR "${errors} reference(s) in the code do not resolve")
endif()
message(STATUS "references: ${checked} references in the code, each to a label the book defines")
