# render.cmake: renders the HTML book and the PDF book (run by the `book` target).
# Inputs (-D): ROOT, BOOK_DIR, FIGURE_DIR, PANDOC, PDFLATEX, RSVG_CONVERT, PAPER.
cmake_minimum_required(VERSION 3.25)

function(run_or_fail what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out
                  ERROR_VARIABLE err WORKING_DIRECTORY ${ROOT})
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed:\n${err}\n${out}")
  endif()
endfunction()

# The chapters, in order: chapters/NN-slug/chapter.md.
file(GLOB chapter_files RELATIVE ${ROOT}/chapters ${ROOT}/chapters/[0-9][0-9]-*/chapter.md)
list(SORT chapter_files)
set(dirs)
foreach(file IN LISTS chapter_files)
  get_filename_component(dir ${file} DIRECTORY)
  list(APPEND dirs ${dir})
  file(STRINGS ${ROOT}/chapters/${file} heading LIMIT_COUNT 1 REGEX "^# ")
  string(REGEX REPLACE "^# +" "" heading "${heading}")
  string(REGEX REPLACE " *\\{[^}]*\\} *$" "" heading "${heading}")
  string(SUBSTRING ${dir} 0 2 number)
  math(EXPR number "${number}")
  set(title_${dir} "${heading}")
  set(number_${dir} "${number}")
endforeach()
string(REPLACE ";" " " all_dirs "${dirs}")

file(MAKE_DIRECTORY ${BOOK_DIR} ${BOOK_DIR}/source ${BOOK_DIR}/latex/figures)
file(COPY_FILE ${ROOT}/book/style.css ${BOOK_DIR}/style.css)

set(filter_env EP_ROOT=${ROOT} EP_FIGURES=${FIGURE_DIR} EP_ALL_CHAPTERS=${all_dirs}
    EP_OUT=${BOOK_DIR} EP_LATEX_FIGURES=${BOOK_DIR}/latex/figures)
set(html_options --from=markdown --to=html5 --standalone --mathml
    --template=${ROOT}/book/template.html --lua-filter=${ROOT}/book/filters/exactpixels.lua
    --highlight-style=pygments --metadata-file=${ROOT}/book/metadata.yaml)

# One HTML page per chapter, with previous/next links.
list(LENGTH dirs count)
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  list(GET dirs ${i} dir)
  set(nav)
  if(i GREATER 0)
    math(EXPR p "${i} - 1")
    list(GET dirs ${p} prev)
    list(APPEND nav -V prev=${prev}.html "-Vprev-title=${number_${prev}}. ${title_${prev}}")
  endif()
  if(i LESS last)
    math(EXPR n "${i} + 1")
    list(GET dirs ${n} next)
    list(APPEND nav -V next=${next}.html "-Vnext-title=${number_${next}}. ${title_${next}}")
  endif()
  run_or_fail("HTML of chapters/${dir}/chapter.md"
    ${CMAKE_COMMAND} -E env ${filter_env} EP_TARGET=html EP_CHAPTERS=${dir}
    ${PANDOC} ${html_options} ${nav} chapters/${dir}/chapter.md -o ${BOOK_DIR}/${dir}.html)
endforeach()

# The contents page.
set(index "---\npagetitle: Contents\n---\n\n# Exact Pixels\n\n")
string(APPEND index "*Triangle rasterization and texture mapping, every pixel accounted for.*\n\n")
string(APPEND index "::: toc\n")
foreach(dir IN LISTS dirs)
  string(APPEND index "1. [Chapter ${number_${dir}}: ${title_${dir}}](${dir}.html)\n")
endforeach()
string(APPEND index ":::\n\n")
string(APPEND index "Also: [the PDF book](exact-pixels.pdf) · [the API reference](api/index.html)\n")
file(WRITE ${BOOK_DIR}/latex/index.md "${index}")
run_or_fail("HTML contents page"
  ${PANDOC} --from=markdown --to=html5 --standalone --template=${ROOT}/book/template.html
  --metadata-file=${ROOT}/book/metadata.yaml ${BOOK_DIR}/latex/index.md
  -o ${BOOK_DIR}/index.html)

# The PDF: SVG figures become PDF, then one LaTeX document of all chapters.
file(GLOB svgs ${FIGURE_DIR}/*.svg)
foreach(svg IN LISTS svgs)
  get_filename_component(name ${svg} NAME_WE)
  run_or_fail("Converting ${svg} to PDF"
    ${RSVG_CONVERT} --format=pdf --output=${BOOK_DIR}/latex/figures/${name}.pdf ${svg})
endforeach()
set(chapter_paths)
foreach(dir IN LISTS dirs)
  list(APPEND chapter_paths chapters/${dir}/chapter.md)
endforeach()
if(PAPER STREQUAL "letter")
  set(papersize letter)
else()
  set(papersize a4)
endif()
run_or_fail("LaTeX of the book"
  ${CMAKE_COMMAND} -E env ${filter_env} EP_TARGET=latex "EP_CHAPTERS=${all_dirs}"
  ${PANDOC} --from=markdown --to=latex --standalone --top-level-division=chapter
  --number-sections --toc --toc-depth=2 --highlight-style=pygments
  --lua-filter=${ROOT}/book/filters/exactpixels.lua
  --metadata-file=${ROOT}/book/metadata.yaml
  --include-in-header=${ROOT}/book/latex/header.tex
  -V documentclass=book -V classoption=oneside -V papersize=${papersize}
  -V fontsize=10pt -V geometry=margin=22mm
  ${chapter_paths} -o ${BOOK_DIR}/latex/exact-pixels.tex)
foreach(pass 1 2)
  execute_process(COMMAND ${PDFLATEX} -interaction=nonstopmode -halt-on-error
                    exact-pixels.tex
                  WORKING_DIRECTORY ${BOOK_DIR}/latex RESULT_VARIABLE result
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    string(REGEX MATCH "![^\n]*\n[^\n]*\n[^\n]*\n[^\n]*" first_error "${out}")
    message(FATAL_ERROR "pdflatex failed (see ${BOOK_DIR}/latex/exact-pixels.log):\n"
                        "${first_error}")
  endif()
endforeach()
file(COPY_FILE ${BOOK_DIR}/latex/exact-pixels.pdf ${BOOK_DIR}/exact-pixels.pdf)
message(STATUS "Book: ${BOOK_DIR}/index.html and ${BOOK_DIR}/exact-pixels.pdf")
