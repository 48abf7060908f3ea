# A kit builds with CMake 3.16 (Ubuntu 20.04's, the oldest a student is likely to have):
# run by CTest as
#   cmake -DROOT=<source tree> -DMAKE_KIT=<make-kit> -DWORK=<folder> -P this file
# It makes chapter 7's kit (the one with the most CMake: every layer) and reads every
# CMake file in it. The kit must say cmake_minimum_required(VERSION 3.16...), carry no
# CMakePresets.json, and use only the commands, keywords, generator expressions and
# variables listed below, each of which CMake 3.16's documentation has (the version that
# added it is noted where it is after 3.0). A kit that uses anything else fails here:
# check the CMake documentation of version 3.16 for it, then add it with its version, or
# write it another way.
cmake_minimum_required(VERSION 3.25)
set(commands # every command here is in CMake 3.0 unless noted
  add_compile_options add_custom_target add_dependencies add_executable add_library
  add_subdirectory add_test
  check_cxx_source_compiles # the module CheckCXXSourceCompiles
  cmake_minimum_required continue # 3.2
  else elseif endforeach endfunction endif endmacro endwhile enable_testing file
  find_package find_path foreach function if include list macro message option
  pkg_check_modules project return set set_property set_target_properties
  set_tests_properties string target_compile_definitions target_compile_options
  target_include_directories target_link_libraries while
  target_sources # 3.1
  )
set(keywords
  # arguments of commands
  AND APPEND CACHE COMMAND CONFIG DEPENDS FORCE GLOB IMPORTED IN INTERFACE IS_DIRECTORY
  LABELS LANGUAGES LISTS NAME NOT OR PATHS PATH_SUFFIXES PRIVATE PROPERTIES PUBLIC
  REGEX REPLACE REQUIRED STATIC STATUS STRING STRINGS TARGET TOUPPER VERBATIM VERSION
  WORKING_DIRECTORY FATAL_ERROR WARNING EXISTS DEFINED STREQUAL
  CONFIGURE_DEPENDS # file(GLOB), 3.12
  POP_FRONT         # list(), 3.15
  IMPORTED_TARGET   # pkg_check_modules, 3.6
  USES_TERMINAL     # add_custom_target, 3.2
  GENERATE OUTPUT CONTENT # file(GENERATE ... CONTENT), 3.2
  MATCHES OBJECT # if(... MATCHES ...), add_library(... OBJECT ...)
  # values and CMake's variables
  CXX ON OFF
  CMAKE_BUILD_TYPE CMAKE_CONFIGURATION_TYPES CMAKE_CXX_EXTENSIONS CMAKE_CXX_STANDARD
  CMAKE_CXX_STANDARD_REQUIRED
  CMAKE_EXPORT_COMPILE_COMMANDS # 3.5
  CMAKE_RUNTIME_OUTPUT_DIRECTORY INTERFACE_INCLUDE_DIRECTORIES CMAKE_SYSTEM_PROCESSOR
  # the find modules' names, as find_package and pkg_check_modules take them
  PNG CLI11
  # the kit's own names: options, variables, prefixes, compile definitions
  STB TOMLPP LAYER EXACTPIXELS_BENCH EXACTPIXELS_BINARY_DIR EXACTPIXELS_BOOK
  EXACTPIXELS_CLI EXACTPIXELS_GRADE_CMAKE EXACTPIXELS_HAS_ EXACTPIXELS_KIT_STAMP
  EXACTPIXELS_LAYERS EXACTPIXELS_SCENES_DIR EXACTPIXELS_SOURCE_DIR EXACTPIXELS_VERSION
  EXACTPIXELS_WERROR EXAMPLE_SOURCES GLM_FORCE_CXX17 SUPPORT_SOURCES TEST_SOURCES
  STB_INCLUDE_DIR EXACTPIXELS_LIBCXX TINYOBJLOADER_USE_DOUBLE)
set(generator_expressions BOOL TARGET_FILE TARGET_OBJECTS)

file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${MAKE_KIT} kit --source ${ROOT} --template ${ROOT}/src/kits/template
                        --chapter 07 --out ${WORK}/ch07
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "make-kit failed:\n${output}")
endif()
if(EXISTS ${WORK}/ch07/CMakePresets.json OR EXISTS ${WORK}/ch07/CMakeUserPresets.json)
  message(FATAL_ERROR "the kit carries CMake presets, which need CMake 3.19 or later")
endif()
file(STRINGS ${WORK}/ch07/CMakeLists.txt minimum REGEX "^cmake_minimum_required")
if(NOT minimum MATCHES "^cmake_minimum_required\\(VERSION 3\\.16(\\.\\.\\.[0-9.]+)?\\)$")
  message(FATAL_ERROR "the kit's CMakeLists.txt says '${minimum}', not "
                      "cmake_minimum_required(VERSION 3.16...)")
endif()

file(GLOB_RECURSE files ${WORK}/ch07/CMakeLists.txt ${WORK}/ch07/*.cmake)
set(problems)
set(count 0)
foreach(file IN LISTS files)
  file(RELATIVE_PATH rel ${WORK}/ch07 ${file})
  file(STRINGS ${file} lines)
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    # Quoted text and comments are not CMake code; ${variables} are the kit's.
    string(REGEX REPLACE "\"[^\"]*\"" "" code "${line}")
    string(REGEX REPLACE "#.*$" "" code "${code}")
    string(REGEX REPLACE "\\$\\{[^}]*\\}" "" code "${code}")
    if(code MATCHES "^[ \t]*([A-Za-z_][A-Za-z0-9_]*)[ \t]*\\(")
      string(TOLOWER "${CMAKE_MATCH_1}" command)
      math(EXPR count "${count} + 1")
      if(NOT command IN_LIST commands)
        list(APPEND problems "${rel}:${number}: command ${command}()")
      endif()
    endif()
    string(REGEX MATCHALL "\\$<[A-Z_]+" expressions "${code}")
    foreach(expression IN LISTS expressions)
      string(SUBSTRING "${expression}" 2 -1 expression)
      if(NOT expression IN_LIST generator_expressions)
        list(APPEND problems "${rel}:${number}: generator expression $<${expression}>")
      endif()
    endforeach()
    string(REGEX REPLACE "\\$<[A-Z_]+" "" code "${code}")
    # Upper-case words not part of a longer name (PkgConfig::STB, glm::glm, -Werror).
    string(REGEX MATCHALL "(^|[ \t(])[A-Z][A-Z0-9_]+([ \t)]|$)" words "${code}")
    foreach(word IN LISTS words)
      string(REGEX REPLACE "[ \t()]" "" word "${word}")
      if(NOT word IN_LIST keywords)
        list(APPEND problems "${rel}:${number}: keyword or variable ${word}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(count LESS 20)
  message(FATAL_ERROR "read only ${count} commands in ${files}: is this a kit?")
endif()
if(problems)
  list(REMOVE_DUPLICATES problems)
  string(REPLACE ";" "\n  " problems "${problems}")
  message(FATAL_ERROR "the kit uses what this list does not know to be in CMake 3.16 "
                      "(see the top of ${CMAKE_CURRENT_LIST_FILE}):\n  ${problems}")
endif()
message(STATUS "the kit's ${count} CMake commands are all in CMake 3.16")
