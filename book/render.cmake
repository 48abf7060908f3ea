# render.cmake: renders the HTML book and the PDF book (run by the `book` target).
# Inputs (-D): ROOT, BOOK_DIR, FIGURE_DIR, PANDOC, PDFLATEX, MAKEINDEX, RSVG_CONVERT, PAPER,
# LIVE_DIR (where web/'s WebAssembly build put exactpixels-live.js) and EDITION, one of
#   public   the public book (`book`): every listing whole, no worked solutions;
#   course   the course edition (`book-course`): every exercise region in a listing shown
#            as its stub, as the students' kits have it; no worked solutions;
#   teacher  the teacher's edition (`book-teacher`): the public book plus the worked
#            solutions.
# The course and teacher's editions say which they are on every HTML page (a banner) and
# at the foot of every PDF page, so that neither is mistaken for the other. Every edition's
# title (the contents page, the PDF's title page) names the book's edition
# (`book-edition` in book/metadata.yaml, whose changes book/CHANGELOG.md lists), VERSION
# (the project's) and the commit of ROOT (src/kits/source_commit.cmake), as the kits do.
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

# "Edition 1, version 0.1.0, commit 0123456789ab": which book this is, for the title.
# The changelog's newest entry ("## Edition N, version V ...") must be this edition and
# version: a new edition or version without its entry fails the build.
file(STRINGS ${ROOT}/book/metadata.yaml edition_entry REGEX "^book-edition:")
string(REGEX REPLACE "^book-edition: *\"?([^\"]*)\"? *$" "\\1" book_edition "${edition_entry}")
if(NOT book_edition MATCHES "^[0-9]+$")
  message(FATAL_ERROR "book/metadata.yaml: no line 'book-edition: N' (found '${edition_entry}')")
endif()
file(STRINGS ${ROOT}/book/CHANGELOG.md newest REGEX "^## " LIMIT_COUNT 1)
if(NOT newest MATCHES "^## Edition ${book_edition}, version ${VERSION}[ ,(]")
  message(FATAL_ERROR "book/CHANGELOG.md: the newest entry is '${newest}', not "
                      "'## Edition ${book_edition}, version ${VERSION} ...' (book-edition in "
                      "book/metadata.yaml, the version in CMakeLists.txt)")
endif()
include(${ROOT}/src/kits/source_commit.cmake)
source_commit(${ROOT} book_commit)
set(edition_line "Edition ${book_edition}, version ${VERSION}, commit ${book_commit}")

file(MAKE_DIRECTORY ${BOOK_DIR} ${BOOK_DIR}/source ${BOOK_DIR}/latex/figures)
file(COPY_FILE ${ROOT}/book/style.css ${BOOK_DIR}/style.css)
# The pages show figures from figures/ beside them: an edition rendered outside the
# figure folder's book (the course and teacher's editions) gets its own copy.
get_filename_component(figure_parent ${FIGURE_DIR} DIRECTORY)
if(NOT figure_parent STREQUAL BOOK_DIR)
  file(GLOB figure_images ${FIGURE_DIR}/*.svg ${FIGURE_DIR}/*.png)
  file(REMOVE_RECURSE ${BOOK_DIR}/figures)
  file(COPY ${figure_images} DESTINATION ${BOOK_DIR}/figures)
endif()

# The live figures' module (LIVE_DIR, the book's web/ build) and their script.
file(REMOVE_RECURSE ${BOOK_DIR}/live)
if(LIVE_DIR)
  file(COPY ${LIVE_DIR}/exactpixels-live.js ${ROOT}/web/live.js DESTINATION ${BOOK_DIR}/live)
endif()

set(filter_env EP_ROOT=${ROOT} EP_FIGURES=${FIGURE_DIR} EP_ALL_CHAPTERS=${all_dirs}
    EP_OUT=${BOOK_DIR} EP_LATEX_FIGURES=${BOOK_DIR}/latex/figures)
# Citations: after the book's filter, citeproc with the committed bibliography and style
# (no network); each chapter page and the PDF end with the works they cite.
set(citation_options --citeproc --bibliography=${ROOT}/book/references.bib
    --csl=${ROOT}/book/exact-pixels.csl -M reference-section-title=References)
set(edition_banner)
if(EDITION STREQUAL "teacher")
  list(APPEND filter_env EP_TEACHER=1)
  set(edition_banner "Teacher's edition — not for students")
elseif(EDITION STREQUAL "course")
  list(APPEND filter_env EP_COURSE=1)
  set(edition_banner "Course edition")
elseif(NOT EDITION STREQUAL "public")
  message(FATAL_ERROR "EDITION must be public, course or teacher, not '${EDITION}'")
endif()
set(edition_html)
set(edition_latex)
file(MAKE_DIRECTORY ${BOOK_DIR}/latex)
file(WRITE ${BOOK_DIR}/latex/edition.tex "% The public book has no edition line.\n")
if(edition_banner)
  list(APPEND filter_env "EP_EDITION=${edition_banner}")
  set(edition_html "-Vedition=${edition_banner}")
  # At the foot of every page, below the page number, chapter openings included: a
  # shipout hook, which no page style can leave out.
  string(REPLACE "—" "---" latex_banner "${edition_banner}")
  file(WRITE ${BOOK_DIR}/latex/edition.tex
    "\\AddToHook{shipout/foreground}{%\n"
    "  \\put(0,0){\\raisebox{\\dimexpr-\\paperheight+12mm\\relax}[0pt][0pt]{%\n"
    "    \\makebox[\\paperwidth]{\\small\\sffamily\\bfseries ${latex_banner}}}}}\n")
endif()
# book/filters/live.lua first: the live figures (HTML only; dropped from the PDF).
set(html_options --from=markdown --to=html5 --standalone --mathml
    --template=${ROOT}/book/template.html --lua-filter=${ROOT}/book/filters/live.lua
    --lua-filter=${ROOT}/book/filters/exactpixels.lua
    ${citation_options} ${edition_html}
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

# Pages that are not chapters (book/NAME.md): HTML pages of their own, and appendices of
# the PDF in this order.
set(pages build-and-run input-limits measuring teaching assessment glossary CHANGELOG)

# The contents page: every chapter with its numbered sections (the filter reads them from
# the chapters), then the appendix pages.
set(index "---\npagetitle: Contents\n---\n\n# Exact Pixels\n\n")
string(APPEND index "*Triangle rasterization and texture mapping, every pixel accounted for.*\n\n")
string(APPEND index "[${edition_line}]{.edition-line} ([changes](CHANGELOG.html))\n\n")
string(APPEND index "::: contents\n:::\n\n")
string(APPEND index "::: appendices\n")
foreach(page IN LISTS pages)
  file(STRINGS ${ROOT}/book/${page}.md heading LIMIT_COUNT 1 REGEX "^# ")
  string(REGEX REPLACE "^# +" "" heading "${heading}")
  string(REGEX REPLACE " *\\{[^}]*\\} *$" "" heading "${heading}")
  string(APPEND index "- [${heading}](${page}.html)\n")
endforeach()
string(APPEND index ":::\n\n")
string(APPEND index "Also: [the PDF book](exact-pixels.pdf) · [the API reference](api/index.html)\n")
file(WRITE ${BOOK_DIR}/latex/index.md "${index}")
run_or_fail("HTML contents page"
  ${CMAKE_COMMAND} -E env ${filter_env} EP_TARGET=html EP_PAGE=${BOOK_DIR}/latex/index.md
  ${PANDOC} ${html_options} ${BOOK_DIR}/latex/index.md -o ${BOOK_DIR}/index.html)

foreach(page IN LISTS pages)
  run_or_fail("HTML of book/${page}.md"
    ${CMAKE_COMMAND} -E env ${filter_env} EP_TARGET=html EP_PAGE=book/${page}.md
    ${PANDOC} ${html_options} book/${page}.md -o ${BOOK_DIR}/${page}.html)
endforeach()

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
# The back matter: the pages above as appendices, then the index of terms.
# Pandoc's template says \backmatter before this, which would leave the appendices
# unnumbered: number them again (without \mainmatter, which restarts the page numbers).
set(back "\\makeatletter\\@mainmattertrue\\makeatother\n\\appendix\n")
foreach(page IN LISTS pages)
  run_or_fail("LaTeX of book/${page}.md"
    ${CMAKE_COMMAND} -E env ${filter_env} EP_TARGET=latex EP_PAGE=book/${page}.md
    ${PANDOC} --from=markdown --to=latex --top-level-division=chapter --number-sections
    --lua-filter=${ROOT}/book/filters/exactpixels.lua book/${page}.md
    -o ${BOOK_DIR}/latex/${page}.tex)
  file(READ ${BOOK_DIR}/latex/${page}.tex text)
  string(APPEND back "${text}\n")
endforeach()
string(APPEND back "\\backmatter\n\\cleardoublepage\\phantomsection\\addcontentsline{toc}{chapter}{Index}\n")
string(APPEND back "\\printindex\n")
file(WRITE ${BOOK_DIR}/latex/back-matter.tex "${back}")
# The same 155 mm text block on both papers (about 80 characters of 11 pt text a line, and
# 90 columns of the listing font, see latex/header.tex); the margins take the difference.
run_or_fail("LaTeX of the book"
  ${CMAKE_COMMAND} -E env ${filter_env} EP_TARGET=latex "EP_CHAPTERS=${all_dirs}"
  ${PANDOC} --from=markdown --to=latex --standalone --top-level-division=chapter
  --number-sections --toc --toc-depth=2 --highlight-style=pygments
  --lua-filter=${ROOT}/book/filters/live.lua
  --lua-filter=${ROOT}/book/filters/exactpixels.lua ${citation_options}
  --metadata-file=${ROOT}/book/metadata.yaml "--metadata=date:${edition_line}"
  --include-in-header=${ROOT}/book/latex/header.tex
  --include-in-header=${BOOK_DIR}/latex/edition.tex
  --include-after-body=${BOOK_DIR}/latex/back-matter.tex
  -V documentclass=book -V classoption=oneside -V papersize=${papersize}
  -V fontsize=11pt -V geometry=textwidth=155mm -V geometry=top=25mm
  -V geometry=bottom=30mm
  ${chapter_paths} -o ${BOOK_DIR}/latex/exact-pixels.tex)
# Three passes with makeindex after the first: the second places the index and the
# contents, the third settles page numbers that moved. max_print_line keeps each log
# message on one line for the PDF check.
file(REMOVE ${BOOK_DIR}/latex/exact-pixels.ind)
foreach(pass 1 2 3)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env max_print_line=10000
                    ${PDFLATEX} -interaction=nonstopmode -halt-on-error exact-pixels.tex
                  WORKING_DIRECTORY ${BOOK_DIR}/latex RESULT_VARIABLE result
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    string(REGEX MATCH "![^\n]*\n[^\n]*\n[^\n]*\n[^\n]*" first_error "${out}")
    message(FATAL_ERROR "pdflatex failed (see ${BOOK_DIR}/latex/exact-pixels.log):\n"
                        "${first_error}")
  endif()
  if(pass EQUAL 1)
    execute_process(COMMAND ${MAKEINDEX} -q exact-pixels.idx
                    WORKING_DIRECTORY ${BOOK_DIR}/latex RESULT_VARIABLE result
                    ERROR_VARIABLE err)
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "makeindex failed (see ${BOOK_DIR}/latex/exact-pixels.ilg):\n${err}")
    endif()
  endif()
endforeach()
file(COPY_FILE ${BOOK_DIR}/latex/exact-pixels.pdf ${BOOK_DIR}/exact-pixels.pdf)
message(STATUS "Book: ${BOOK_DIR}/index.html and ${BOOK_DIR}/exact-pixels.pdf")
