-- exactpixels.lua: the Pandoc filter that makes the book and the code one.
--
-- It pulls listings from compiled source by region name, splices generated Markdown
-- (measured tables), numbers equations, figures, listings, tables and sections per
-- chapter, resolves @eq: @fig: @lst: @tbl: @sec: references (across chapters too),
-- checks that every test the text names exists, and refuses hand-typed code blocks.
-- Any broken reference fails the build with "chapter file:line: what is wrong".
--
-- Environment (set by book/CMakeLists.txt):
--   EP_ROOT          the source tree
--   EP_FIGURES       the folder the figure programs wrote into
--   EP_TARGET        html or latex
--   EP_CHAPTERS      the chapter folders of this run, in order (e.g. "01-gradients")
--   EP_ALL_CHAPTERS  every chapter folder of the book, in order (for cross references)
--   EP_OUT           the HTML output folder (source pages of named tests go below it)
--   EP_LATEX_FIGURES the folder where SVG figures were converted to PDF (LaTeX only)
--   EP_TEACHER       "1" for the teacher's edition: `::: solution` blocks are kept (the
--                    student book drops them)
--   EP_COURSE        "1" for the course edition: every exercise region in a listing is
--                    shown as its stub, as the student's kit has it (see "Listings pulled
--                    from source" below); the public book shows the solution
--                    and text marked for the public book only is replaced by its course
--                    variant (see "Text of one edition" below)
--   EP_EDITION       the edition's banner ("Course edition", ...), shown on the source
--                    pages this filter writes (the chapters get it from the template)
--   EP_PAGE          set for a page that is not a chapter (the contents page, the
--                    glossary, "Build and run"): the path of its Markdown file, for error
--                    messages. Its headings are not numbered, its references and named
--                    tests resolve as in a chapter, and a `::: contents` block in it is
--                    filled with every chapter's numbered headings (the table of contents).
--
-- Teaching structure (book/AUTHORING.md, "Objectives, exercises and solutions"): every
-- chapter has one `::: objectives` block (a list of what the reader will be able to do)
-- before its first section; every item of the list under "## Exercises" begins with
-- []{.exercise kind=derive|implement|measure marks=1|2|3 difficulty=easy|medium|hard
-- objectives="1,3"} (the numbers of the chapter's objectives it checks; region=ID for an
-- exercise of the kits), rendered "[kind, N marks, difficulty; objectives 1, 3]";
-- a `::: solution` block inside an exercise is its worked solution, dropped from the
-- student book and kept, headed "Solution.", in the teacher's edition.
--
-- In every document, [term]{.index} marks a term for the PDF's index (\index{term}; HTML
-- shows the text only); [text]{.index term="edge function!top-left bias"} files the text
-- under another entry (makeindex syntax: "!" for a sub-entry).

local root = assert(os.getenv("EP_ROOT"), "EP_ROOT not set")
local figures = assert(os.getenv("EP_FIGURES"), "EP_FIGURES not set")
local target = os.getenv("EP_TARGET") or "html"
local out_dir = os.getenv("EP_OUT") or "."
local latex_figures = os.getenv("EP_LATEX_FIGURES") or figures

local function split(text)
  local items = {}
  for item in (text or ""):gmatch("%S+") do items[#items + 1] = item end
  return items
end
local chapters_here = split(os.getenv("EP_CHAPTERS"))
local page_file = os.getenv("EP_PAGE")
local all_chapters = split(os.getenv("EP_ALL_CHAPTERS"))

local function read_file(path)
  local file = io.open(path, "r")
  if not file then return nil end
  local text = file:read("a")
  file:close()
  return text
end

local function lines_of(text)
  local lines = {}
  for line in (text .. "\n"):gmatch("(.-)\r?\n") do lines[#lines + 1] = line end
  if lines[#lines] == "" then lines[#lines] = nil end
  return lines
end

local function chapter_file(dir) return "chapters/" .. dir .. "/chapter.md" end
local function chapter_number(dir) return tonumber(dir:sub(1, 2)) end

-- The line of the chapter file where `needle` first appears, for error messages.
local function line_of(dir, needle)
  local text = read_file(root .. "/" .. chapter_file(dir)) or ""
  local n = 0
  for line in (text .. "\n"):gmatch("(.-)\n") do
    n = n + 1
    if line:find(needle, 1, true) then return n end
  end
  return 0
end

-- Stops the build with "chapters/NN-slug/chapter.md:LINE: message" and a non-zero status.
local function fail(dir, needle, message)
  if not dir and page_file then
    local n = 0
    for number, line in ipairs(lines_of(read_file(page_file) or "")) do
      if line:find(needle, 1, true) then n = number break end
    end
    io.stderr:write(string.format("%s:%d: error: %s\n", page_file, n, message))
    os.exit(1)
  end
  io.stderr:write(string.format("%s:%d: error: %s\n", chapter_file(dir or "??"),
    line_of(dir or "", needle), message))
  os.exit(1)
end

-- Undoes Pandoc's smart typography, so text can be compared with source code.
local function plain(text)
  local replacements = { ["\u{2013}"] = "--", ["\u{2014}"] = "---", ["\u{2018}"] = "'",
    ["\u{2019}"] = "'", ["\u{201C}"] = '"', ["\u{201D}"] = '"', ["\u{2026}"] = "...",
    ["\u{a0}"] = " " }
  for from, to in pairs(replacements) do text = text:gsub(from, to) end
  return text
end

---------------------------------------------------------------------------------------
-- Fence text. A `:::` or ``` line that Pandoc did not read as a fence (a closing `:::`
-- sharing its line with text, a fence never closed) reaches the reader as text, as
-- chapter 3's "::: erratum ... ::: The parabola" once did. Every such word fails the
-- build, each reported with the line of the source it came from.

local function is_fence_word(text)
  return text:sub(1, 3) == ":::" or text:sub(1, 3) == "```"
end

-- Up to `count` words of `inlines` from position k on (Str only, smart quotes undone),
-- stopping at the first inline that is not a word or a space.
local function words_from(inlines, k, count)
  local words = {}
  for i = k, #inlines do
    local inline = inlines[i]
    if inline.t == "Str" then
      words[#words + 1] = plain(inline.text)
      if #words == count then break end
    elseif inline.t ~= "Space" and inline.t ~= "SoftBreak" then
      break
    end
  end
  return words
end

-- The first line of `lines` whose words, read on over the next lines, begin with `words`;
-- failing that, the first line holding the first two of them; failing that, 0.
local function line_of_words(lines, words)
  for n = 1, #lines do
    local tokens = {}
    for m = n, math.min(n + 4, #lines) do
      for token in lines[m]:gmatch("%S+") do tokens[#tokens + 1] = token end
    end
    local match = #tokens >= #words and lines[n]:find("%S") ~= nil -- it starts on line n
    for i = 1, #words do
      if tokens[i] ~= words[i] then match = false break end
    end
    if match then return n end
  end
  local needle = table.concat(words, " ", 1, math.min(2, #words))
  for n, line in ipairs(lines) do
    if line:find(needle, 1, true) then return n end
  end
  return 0
end

-- Fails the build if any block of `blocks` shows fence text. `source_of(block)` gives the
-- file the block came from (for the message) and the text of that file.
local function refuse_fence_text(blocks, source_of)
  local problems = {}
  for _, block in ipairs(blocks) do
    local file, text = source_of(block)
    pandoc.Pandoc({ block }):walk({
      Inlines = function(inlines)
        for k, inline in ipairs(inlines) do
          if inline.t == "Str" and is_fence_word(inline.text) then
            local words = words_from(inlines, k, 6)
            local line = line_of_words(lines_of(text or ""), words)
            problems[#problems + 1] = string.format("%s:%d: error: fence text reaches the "
              .. "page: '%s' (a ::: or ``` line Pandoc did not read as a fence; a closing "
              .. "fence stands on a line of its own)", file, line, table.concat(words, " "))
          end
        end
      end,
    })
  end
  if #problems > 0 then
    io.stderr:write(table.concat(problems, "\n") .. "\n")
    os.exit(1)
  end
end

---------------------------------------------------------------------------------------
-- Recognising numbered things

local function equation_label(block)
  if block.t ~= "Para" then return nil end
  local c = block.content
  if #c >= 1 and c[1].t == "Math" and c[1].mathtype == "DisplayMath" then
    local last = c[#c]
    if #c >= 2 and last.t == "Str" then
      local label = last.text:match("^{#(eq:[%w%-_]+)}$")
      if label then return label, c[1].text end
    end
    if #c == 1 then return "", c[1].text end
  end
  return nil
end

local function figure_image(block)
  if block.t == "Para" and #block.content == 1 and block.content[1].t == "Image"
      and #block.content[1].caption > 0 then
    return block.content[1]
  end
  return nil
end

local function table_label(block)
  if block.t ~= "Table" then return nil end
  local caption = block.caption.long
  if #caption == 0 then return nil end
  local inlines = caption[#caption].content
  local last = inlines[#inlines]
  if last and last.t == "Str" then
    local label = last.text:match("^{#(tbl:[%w%-_]+)}$")
    if label then return label end
  end
  return ""
end

local function is_unnumbered(header)
  return header.classes:includes("unnumbered")
end

---------------------------------------------------------------------------------------
-- Numbering: one traversal order, used both to collect labels from every chapter and
-- to render this run's chapters, so the numbers always agree.

local function new_counters(dir)
  return { dir = dir, number = chapter_number(dir), eq = 0, fig = 0, lst = 0, tbl = 0,
           sec = 0, subsec = 0 }
end

-- Calls visit(block, counters) for every block in document order, descending into
-- divs, quotes and lists. Level-1 headers move to the next chapter of `dirs`.
local function each_block(blocks, state, visit)
  for _, block in ipairs(blocks) do
    if block.t == "Header" and block.level == 1 then
      state.h1 = state.h1 + 1
      local dir = state.dirs[state.h1]
      if not dir then error("more level-1 headings than chapters in this run", 0) end
      state.counters = new_counters(dir)
    end
    visit(block, state.counters)
    if block.t == "Div" or block.t == "BlockQuote" then
      each_block(block.content, state, visit)
    elseif block.t == "BulletList" or block.t == "OrderedList" then
      for _, item in ipairs(block.content) do each_block(item, state, visit) end
    elseif block.t == "CodeBlock" and block.classes:includes("generated") then
      local text = read_file(figures .. "/" .. (block.attributes.file or ""))
      if text then each_block(pandoc.read(text, "markdown").blocks, state, visit) end
    end
  end
end

-- Advances the counters for `block`; returns kind and number text when it is numbered.
local function number_of(block, counters)
  if not counters then return nil end
  local n = counters.number
  if block.t == "Header" and block.level == 1 then
    return "ch", tostring(n)
  elseif block.t == "Header" and block.level == 2 and not is_unnumbered(block) then
    counters.sec = counters.sec + 1
    counters.subsec = 0
    return "sec", string.format("%d.%d", n, counters.sec)
  elseif block.t == "Header" and block.level == 3 and not is_unnumbered(block) then
    counters.subsec = counters.subsec + 1
    return "sec", string.format("%d.%d.%d", n, counters.sec, counters.subsec)
  elseif equation_label(block) and equation_label(block) ~= "" then
    counters.eq = counters.eq + 1
    return "eq", string.format("%d.%d", n, counters.eq)
  elseif figure_image(block) then
    counters.fig = counters.fig + 1
    return "fig", string.format("%d.%d", n, counters.fig)
  elseif block.t == "CodeBlock" and block.classes:includes("snippet") then
    counters.lst = counters.lst + 1
    return "lst", string.format("%d.%d", n, counters.lst)
  elseif table_label(block) then
    counters.tbl = counters.tbl + 1
    return "tbl", string.format("%d.%d", n, counters.tbl)
  end
  return nil
end

local function label_of(block)
  if block.t == "Header" then return block.identifier end
  local eq = equation_label(block)
  if eq then return eq end
  local image = figure_image(block)
  if image then return image.identifier end
  if block.t == "CodeBlock" then return block.identifier end
  return table_label(block)
end

-- The course edition gives students the book without the answers to their assignments:
-- an exercise region (`//> exercise ID: hint` ... `//< exercise ID`, book/AUTHORING.md)
-- inside a listing is shown as the kit shows it, its stub lines (`//|`, uncommented)
-- between comments that name the exercise by its number in the chapter's Exercises list,
-- and none of its solution lines. The other editions show the solution and drop the stub.
local course = os.getenv("EP_COURSE") == "1"

-- Text of one edition. Where the text around an exercise would state its answer, the
-- chapter gives the course edition its own wording:
--   ::: not-in-course             [text]{.not-in-course}
--   the public book's text        dropped in the course edition, kept (unwrapped) in the
--   :::                           public book and the teacher's edition
--   ::: course-only               [text]{.course-only}
--   the course edition's text     kept (unwrapped) in the course edition only
--   :::
-- Both may hold anything a chapter may (a labelled equation in each variant keeps its
-- number). The choice is made first, before labels are collected, so every later check
-- sees only the edition's text.
local edition_classes = { ["not-in-course"] = false, ["course-only"] = true }
local function edition_choice(el)
  local choice
  for class, course_only in pairs(edition_classes) do
    if el.classes:includes(class) then
      if choice ~= nil then
        error("a block or span is both .not-in-course and .course-only", 0)
      end
      choice = course_only == course
    end
  end
  return choice
end
local function for_this_edition(blocks)
  return pandoc.Pandoc(blocks):walk({
    Div = function(div)
      local keep = edition_choice(div)
      if keep == nil then return nil end
      return keep and div.content or {}
    end,
    Span = function(span)
      local keep = edition_choice(span)
      if keep == nil then return nil end
      return keep and span.content or {}
    end,
  }).blocks
end

-- Exercise region ID -> "2.3": chapter number and place in the chapter's Exercises list,
-- read from the []{.exercise ... region=ID} tags (filled by collect_labels).
local exercise_numbers = {}
local function collect_exercise_numbers(dir, blocks)
  local in_exercises = false
  for _, block in ipairs(blocks) do
    if block.t == "Header" and block.level <= 2 then
      in_exercises = block.level == 2 and pandoc.utils.stringify(block.content) == "Exercises"
    elseif in_exercises and block.t == "OrderedList" then
      local start = block.listAttributes and block.listAttributes.start or 1
      for index, item in ipairs(block.content) do
        local first = item[1]
        local span = first and (first.t == "Para" or first.t == "Plain") and first.content[1]
        if span and span.t == "Span" and span.attributes.region then
          exercise_numbers[span.attributes.region] =
            string.format("%d.%d", chapter_number(dir), start + index - 1)
        end
      end
    end
  end
end

-- Every label of the book: label -> { kind, number, dir }.
local labels = {}
local function collect_labels()
  for _, dir in ipairs(all_chapters) do
    local text = read_file(root .. "/" .. chapter_file(dir))
    if text then
      local doc = pandoc.read(text, "markdown")
      doc.blocks = for_this_edition(doc.blocks)
      collect_exercise_numbers(dir, doc.blocks)
      local state = { h1 = 0, dirs = { dir } }
      each_block(doc.blocks, state, function(block, counters)
        local kind, number = number_of(block, counters)
        local label = kind and label_of(block)
        -- Only labels written as kind:name are the book's; a heading's automatic id
        -- ("exercises") is local to its page and may repeat from chapter to chapter.
        if label and label:match("^%a+:") then
          if labels[label] then
            fail(dir, label, "label '" .. label .. "' is defined twice")
          end
          labels[label] = { kind = kind, number = number, dir = dir }
        end
      end)
    end
  end
end

-- The table of contents: every chapter's title and numbered level-2 headings, with
-- their numbers, linked to the chapter pages (HTML) or labels (LaTeX).
local function contents_list()
  local chapters = {}
  for _, dir in ipairs(all_chapters) do
    local text = read_file(root .. "/" .. chapter_file(dir))
    if text then
      local doc = pandoc.read(text, "markdown")
      local state = { h1 = 0, dirs = { dir } }
      local entry
      each_block(doc.blocks, state, function(block, counters)
        local kind, number = number_of(block, counters)
        if block.t ~= "Header" or kind ~= (block.level == 1 and "ch" or "sec")
            or block.level > 2 then
          return
        end
        local title = pandoc.utils.stringify(block.content)
        local href = dir .. ".html" .. (block.level == 2 and ("#" .. block.identifier) or "")
        local link = pandoc.Link({ pandoc.Span({ pandoc.Str(number) }, { class = "secnum" }),
                                   pandoc.Space(), pandoc.Str(title) }, href)
        if block.level == 1 then
          entry = { pandoc.Plain({ link }), pandoc.BulletList({}) }
          chapters[#chapters + 1] = entry
        elseif entry then
          entry[2].content:insert({ pandoc.Plain({ link }) })
        end
      end)
    end
  end
  for _, entry in ipairs(chapters) do
    if #entry[2].content == 0 then entry[2] = nil end
  end
  return pandoc.BulletList(chapters)
end

---------------------------------------------------------------------------------------
-- Listings pulled from source

-- Code comments refer to the book by label (@eq:name, @sec:name, ...), so that a number
-- never goes stale; a listing shows the number instead: "eq. 2.8", "section 1.2".
local code_word = { eq = "eq.", fig = "figure", lst = "listing", tbl = "table",
                    sec = "section", ch = "chapter" }
local function resolve_code_references(dir, code)
  return (code:gsub("@(%a+):([%w_%-]*[%w])", function(kind, name)
    local label = kind .. ":" .. name
    if not code_word[kind] then return nil end
    local entry = labels[label]
    if not entry then
      fail(dir, "@" .. label, "unknown reference '@" .. label .. "' in a listing's code")
    end
    return code_word[kind] .. " " .. entry.number
  end))
end

local language_of = { hpp = "cpp", cpp = "cpp", h = "cpp", txt = "text", toml = "toml",
                      cmake = "cmake", lua = "lua", sh = "bash", gp = "gnuplot" }

-- The lines a course-edition listing shows for exercise `id` (at `indent`): a comment
-- naming it, its hint, its stub and a closing comment.
local function exercise_stub(id, indent, hint, stub)
  local number = exercise_numbers[id]
  local name = number and ("Exercise " .. number .. " (" .. id .. ")") or ("Exercise " .. id)
  local lines = { indent .. "// " .. name .. ": your code here." }
  if hint ~= "" then lines[#lines + 1] = indent .. "// Hint: " .. hint end
  for _, line in ipairs(stub) do lines[#lines + 1] = line end
  lines[#lines + 1] = indent .. "// End of " .. name:gsub("^E", "e") .. "."
  return lines
end

local function extract_region(dir, file, name)
  local text = read_file(root .. "/" .. file)
  if not text then fail(dir, file, "snippet file '" .. file .. "' does not exist") end
  local region, inside, found = {}, false, false
  local exercise -- the exercise region being read: { id, indent, hint, stub }
  local hint_goes_on = false -- the line before opened an exercise or continued its hint
  for _, line in ipairs(lines_of(text)) do
    local open = line:match("^%s*//>%s*(.-)%s*$")
    local close = line:match("^%s*//<%s*(.-)%s*$")
    local indent, stub = line:match("^(%s*)//| ?(.*)$")
    -- clang-format wraps a hint too long for its line onto lines "//word" (no space after
    -- the slashes), as make-kit reads them.
    local continuation = hint_goes_on and line:match("^%s*//([^ /<>|!].*)$")
    hint_goes_on = false
    if open == name then
      if found then fail(dir, name, "region '" .. name .. "' appears twice in " .. file) end
      inside, found = true, true
    elseif close == name and inside then
      inside = false
    elseif continuation then
      if exercise then exercise.hint = exercise.hint .. " " .. continuation end
      hint_goes_on = true
    elseif inside and open and open:match("^exercise%s") then
      exercise = { id = open:match("^exercise%s+([%w%-]+)"), indent = line:match("^%s*"),
                   hint = open:match(":%s*(.-)$") or "", stub = {} }
      hint_goes_on = true
    elseif inside and open and open:match("^gives%-away%s") then
      -- Code outside a region that states its answer (book/AUTHORING.md): the course
      -- edition shows its stub, as the kits before the exercise's chapter have it.
      exercise = { id = open:match("^gives%-away%s+([%w%-]+)"), indent = line:match("^%s*"),
                   stub = {}, gives_away = true }
    elseif inside and close and exercise and
        (close:match("^exercise%s") or close:match("^gives%-away%s")) then
      if course and exercise.gives_away then
        local number = exercise_numbers[exercise.id]
        region[#region + 1] = exercise.indent .. "// (Left out here: it would answer exercise "
          .. (number or exercise.id) .. ".)"
        for _, l in ipairs(exercise.stub) do region[#region + 1] = l end
      elseif course then
        for _, l in ipairs(exercise_stub(exercise.id, exercise.indent, exercise.hint,
                                         exercise.stub)) do
          region[#region + 1] = l
        end
      end
      exercise = nil
    elseif inside and stub then
      if exercise then exercise.stub[#exercise.stub + 1] = indent .. stub end
    elseif inside and not open and not close and not (course and exercise) then
      region[#region + 1] = line
    end
  end
  if not found then
    fail(dir, 'name="' .. name .. '"',
      "snippet '" .. name .. "' not found in " .. file .. " (no line '//> " .. name .. "')")
  end
  if inside then fail(dir, name, "region '" .. name .. "' in " .. file .. " is not closed") end
  local indent = math.huge
  for _, line in ipairs(region) do
    if line:match("%S") then indent = math.min(indent, #line:match("^%s*")) end
  end
  if indent == math.huge then indent = 0 end
  for i, line in ipairs(region) do region[i] = line:sub(indent + 1) end
  return table.concat(region, "\n")
end

local allowed_code_classes = { pseudocode = true, text = true, toml = true, sh = true,
                               bash = true, csv = true, markdown = true }

---------------------------------------------------------------------------------------
-- Rendering

local function raw(format, text)
  return pandoc.RawBlock(format, text)
end

local function caption_prefix(word, number)
  return pandoc.Strong({ pandoc.Str(word .. "\u{a0}" .. number .. ":") })
end

local function figure_path(dir, src)
  if src:find("/") then fail(dir, src, "figure '" .. src .. "' must be a file name only") end
  local path = figures .. "/" .. src
  if not read_file(path) then
    fail(dir, src, "figure '" .. src .. "' was not made by the build (no " .. path .. ")")
  end
  if target == "latex" then
    if src:match("%.svg$") then
      local pdf = latex_figures .. "/" .. src:gsub("%.svg$", ".pdf")
      if not read_file(pdf) then fail(dir, src, "no PDF conversion of " .. src) end
      return pdf
    end
    return path
  end
  return "figures/" .. src
end

local render_blocks
local render_inlines

local function render_block(block, counters, state)
  local kind, number = number_of(block, counters)
  local dir = counters and counters.dir
  local html = target == "html"

  if block.t == "Header" then
    if kind == "ch" then
      state.title = pandoc.utils.stringify(block.content)
      if html then
        table.insert(block.content, 1, pandoc.Span({ pandoc.Str(number) }, { class = "secnum" }))
        table.insert(block.content, 2, pandoc.Space())
        return { block }
      end
      return { raw("latex", string.format("\\setcounter{chapter}{%d}", counters.number - 1)),
               block }
    elseif kind == "sec" and html then
      table.insert(block.content, 1, pandoc.Span({ pandoc.Str(number) }, { class = "secnum" }))
      table.insert(block.content, 2, pandoc.Space())
    end
    return { block }
  end

  if kind == "eq" then
    local label, tex = equation_label(block)
    if html then
      local math = pandoc.Para({ pandoc.Math("DisplayMath", tex) })
      local tag = pandoc.Para({ pandoc.Str("(" .. number .. ")") })
      return { pandoc.Div({ math, tag }, { id = label, class = "equation" }) }
    end
    return { raw("latex", "\\begin{equation*}" .. tex .. "\\tag{" .. number .. "}\\label{"
      .. label .. "}\\end{equation*}") }
  end

  if kind == "fig" then
    local image = figure_image(block)
    image.src = figure_path(dir, image.src)
    if html then
      table.insert(image.caption, 1, caption_prefix("Figure", number))
      table.insert(image.caption, 2, pandoc.Space())
    end
    return { block }
  end

  if block.t == "CodeBlock" then
    if block.classes:includes("snippet") then
      local file, name = block.attributes.file, block.attributes.name
      if not file or not name then
        fail(dir, "snippet", "a snippet block needs file=\"...\" and name=\"...\"")
      end
      local code = resolve_code_references(dir, extract_region(dir, file, name))
      local extension = file:match("%.([%w]+)$") or ""
      local listing = pandoc.CodeBlock(code, { class = language_of[extension] or "text" })
      local caption = pandoc.Para({ caption_prefix("Listing", number), pandoc.Space(),
                                    pandoc.Code(file) })
      local label = block.identifier ~= "" and block.identifier or nil
      if html then
        return { pandoc.Div({ caption, listing }, { id = label, class = "listing" }) }
      end
      local anchor = label and raw("latex", "\\phantomsection\\label{" .. label .. "}") or nil
      return { anchor or raw("latex", ""), raw("latex", "\\needspace{4\\baselineskip}"),
               caption, listing }
    elseif block.classes:includes("generated") then
      local file = block.attributes.file or ""
      local text = read_file(figures .. "/" .. file)
      if not text then
        fail(dir, file, "generated fragment '" .. file .. "' was not made by the build")
      end
      -- The fragment's own references, named tests and claims (its table captions cite
      -- equations) resolve like the chapter's: the chapter's inlines were done already.
      local fragment = render_inlines(pandoc.read(text, "markdown"), function() return dir end)
      return render_blocks(fragment.blocks, counters, state)
    end
    for _, class in ipairs(block.classes) do
      if allowed_code_classes[class] then return { block } end
    end
    fail(dir, "```", "a code block typed by hand: pull it from source with .snippet, or "
      .. "mark it .pseudocode / .text / .sh / .toml")
  end

  -- longtable, which Pandoc writes every LaTeX table as, steps LaTeX's table counter
  -- for a table without a caption too, while this filter numbers only captioned tables:
  -- step it back, or every table after an uncaptioned one in a chapter would carry a
  -- number the text's references do not.
  if block.t == "Table" and not html and table_label(block) == nil then
    return { block, raw("latex", "\\addtocounter{table}{-1}") }
  end

  if kind == "tbl" then
    local caption = block.caption.long
    local inlines = caption[#caption].content
    local label = table_label(block)
    if label ~= "" then
      inlines:remove(#inlines)
      if inlines[#inlines] and inlines[#inlines].t == "Space" then inlines:remove(#inlines) end
    end
    if html then
      table.insert(inlines, 1, caption_prefix("Table", number))
      table.insert(inlines, 2, pandoc.Space())
      if label ~= "" then block.identifier = label end
    elseif label ~= "" then
      inlines:insert(pandoc.RawInline("latex", "\\label{" .. label .. "}"))
    end
    return { block }
  end

  if block.t == "Div" or block.t == "BlockQuote" then
    block.content = render_blocks(block.content, counters, state, true)
    -- The boxed divs, styled in HTML by style.css and set in PDF in an environment of
    -- header.tex: ::: erratum, where the book corrects its source (a ruled box headed
    -- "Erratum"), and ::: summary, the chapter's "In short" (a box with a rule down its
    -- left side, which may break across a page; teaching() checks where it stands).
    local environments = { erratum = "eperratum", summary = "epsummary" }
    for class, environment in pairs(environments) do
      if block.t == "Div" and block.classes:includes(class) and not html then
        local out = pandoc.List({ raw("latex", "\\begin{" .. environment .. "}") })
        out:extend(block.content)
        out:insert(raw("latex", "\\end{" .. environment .. "}"))
        return out
      end
    end
    return { block }
  elseif block.t == "BulletList" or block.t == "OrderedList" then
    for i, item in ipairs(block.content) do
      block.content[i] = render_blocks(item, counters, state, true)
    end
    return { block }
  end
  return { block }
end

-- Renders a list of blocks in document order. The traversal mirrors each_block.
render_blocks = function(blocks, counters, state, nested)
  local out = pandoc.List()
  for _, block in ipairs(blocks) do
    if not nested and block.t == "Header" and block.level == 1 then
      state.h1 = state.h1 + 1
      local dir = state.dirs[state.h1]
      if not dir then error("more level-1 headings than chapters in this run", 0) end
      state.counters = new_counters(dir)
      counters = state.counters
    end
    for _, b in ipairs(render_block(block, counters, state)) do out:insert(b) end
  end
  return out
end

---------------------------------------------------------------------------------------
-- References and named tests (inline)

local kind_word = { eq = nil, fig = "Figure", lst = "Listing", tbl = "Table",
                    sec = "Section", ch = "Chapter" }

local function page_of(dir) return dir .. ".html" end

local function reference(label, from_dir)
  local entry = labels[label]
  if not entry then fail(from_dir, "@" .. label, "unknown reference '@" .. label .. "'") end
  local text = entry.kind == "eq" and ("(" .. entry.number .. ")")
    or (kind_word[entry.kind] .. "\u{a0}" .. entry.number)
  if target == "latex" then
    return pandoc.RawInline("latex", "\\hyperref[" .. label .. "]{" .. text .. "}")
  end
  local href = (entry.dir == from_dir and "" or page_of(entry.dir)) .. "#" .. label
  return pandoc.Link({ pandoc.Str(text) }, href, "", { class = "ref" })
end

-- The course and teacher's editions mark every page, these too (EP_EDITION).
local edition = os.getenv("EP_EDITION") or ""
local edition_banner = edition == "" and ""
  or ('<p class="edition-banner">' .. edition:gsub("&", "&amp;"):gsub("<", "&lt;") .. "</p>\n")
local source_pages = {}
local function source_page(file)
  if source_pages[file] then return end
  source_pages[file] = true
  local text = read_file(root .. "/" .. file)
  local doc = pandoc.Pandoc({ pandoc.Header(1, { pandoc.Code(file) }),
    pandoc.CodeBlock(text, { id = "src", class = "cpp numberLines" }) })
  local body = pandoc.write(doc, "html5")
  local page = '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
    .. "<title>" .. file .. " · Exact Pixels</title>\n"
    .. '<link rel="stylesheet" href="../style.css">\n</head>\n<body>\n' .. edition_banner
    .. '<nav class="pager"><a href="../index.html">Contents</a></nav>\n<main class="source">\n'
    .. body .. "\n</main>\n</body>\n</html>\n"
  local path = out_dir .. "/source/" .. file:gsub("/", "_") .. ".html"
  local handle = assert(io.open(path, "w"))
  handle:write(page)
  handle:close()
end

local function test_reference(span, dir)
  local file = span.attributes.file
  local name = plain(pandoc.utils.stringify(span.content))
  if not file then fail(dir, name, "a .test span needs file=\"tests/...\"") end
  local text = read_file(root .. "/" .. file)
  if not text then fail(dir, file, "test file '" .. file .. "' does not exist") end
  local line_number
  local lines = lines_of(text)
  for n, line in ipairs(lines) do
    -- clang-format may put the name on the line after "TEST_CASE(": join them.
    local next = n + 1
    if line:match("TEST_CASE%($") or line:match("TEST_CASE_TEMPLATE%($") then
      line = line .. (lines[next] or ""):gsub("^%s+", "")
      next = next + 1
    end
    -- and may split a long name into adjacent string literals: "abc "\n "def".
    if line:match("TEST_CASE") then
      while line:match('"%s*$') and (lines[next] or ""):match('^%s*"') do
        line = line:gsub('"%s*$', "") .. lines[next]:gsub('^%s*"', "")
        next = next + 1
      end
    end
    if line:find('TEST_CASE("' .. name .. '"', 1, true)
        or line:find('TEST_CASE_TEMPLATE("' .. name .. '"', 1, true) then
      line_number = n
      break
    end
  end
  if not line_number then
    fail(dir, name, "the text names test '" .. name .. "' but " .. file
      .. " has no TEST_CASE(\"" .. name .. "\")")
  end
  if target == "latex" then
    -- \eptest (book/latex/header.tex): a lighter face that breaks like prose.
    local inlines = pandoc.List({ pandoc.RawInline("latex", "\\eptest{") })
    inlines:extend(pandoc.Inlines(name))
    inlines:insert(pandoc.RawInline("latex", "}"))
    return pandoc.Span(inlines, { class = "test" })
  end
  local label = pandoc.Code(name)
  source_page(file)
  local href = "source/" .. file:gsub("/", "_") .. ".html#src-" .. line_number
  return pandoc.Link({ label }, href, file .. ", line " .. line_number, { class = "test" })
end

-- [term]{.index}: the text stays; LaTeX also gets \index{key@shown}, sorted by the
-- plain lower-case key. term="..." names another entry (makeindex syntax, "!" nests).
local function index_term(span)
  if target ~= "latex" then return span.content end
  local shown = plain(span.attributes.term or pandoc.utils.stringify(span.content))
  local function escape(text)
    text = text:gsub('(["@|])', '"%1')
    return (text:gsub("([\\{}$&#^_%%~])", function(c)
      local map = { ["\\"] = "\\textbackslash{}", ["~"] = "\\textasciitilde{}",
                    ["^"] = "\\textasciicircum{}" }
      return map[c] or ("\\" .. c)
    end))
  end
  local parts = {}
  for part in (shown .. "!"):gmatch("(.-)!") do
    local key = part:lower():gsub("[^%w ]", "")
    parts[#parts + 1] = escape(key) .. "@" .. escape(part)
  end
  local out = pandoc.List(span.content)
  out:insert(pandoc.RawInline("latex", "\\index{" .. table.concat(parts, "!") .. "}"))
  return out
end

-- Claims the build checks. A data file in the figure folder (written by a program the
-- build runs, or copied there from a committed, dated full run) holds one fact per line,
-- "NAME VALUE" with VALUE a number; "#" starts a comment.
--   [text]{.claim data="FILE" check="NAME OP X; ..."}: every condition must hold, with OP
--   one of < <= > >= == != and X a number or another NAME; the text is shown unchanged.
--   []{.fact data="FILE" name="NAME" format="%.2f"}: the value itself, formatted.
-- A contradicted claim, an unknown NAME or a missing FILE fails the build with
-- "chapters/NN-slug/chapter.md:LINE: error: ..." quoting the claim.
-- A FILE with a "/" in it is a committed file of the source tree instead (a dated full
-- run, e.g. chapters/05-accuracy-cost/callgrind_results.md). In either kind, each row of
-- a Markdown table is a fact, named by its first cell, whose value is its last cell.
local fact_files = {}
local function facts_of(dir, file, needle)
  if fact_files[file] then return fact_files[file] end
  local committed = file:find("/", 1, true) ~= nil
  local text = read_file((committed and root or figures) .. "/" .. file)
  if not text then
    fail(dir, needle, "claim data '" .. file .. "' "
      .. (committed and "does not exist" or "was not made by the build"))
  end
  local facts = {}
  local scene
  for _, line in ipairs(lines_of(text)) do
    local name, value
    scene = line:match('^: Scene "([^"]+)"') or scene
    if line:match("^|") then
      local cells = {}
      for cell in line:gmatch("|([^|]*)") do cells[#cells + 1] = cell:match("^%s*(.-)%s*$") end
      if #cells >= 3 and cells[#cells] == "" then cells[#cells] = nil end
      -- A row under a caption ': Scene "floor" ...' is named floor/its_first_cell; each
      -- numeric cell is also a fact NAME#k (k = 2 for the second column, and so on).
      local row = (scene and (scene .. "/") or "") .. cells[1]:gsub("%s+", "_")
      for k = 2, #cells do
        local number = tonumber((cells[k]:gsub("%s*%%$", "")))
        if number then facts[row .. "#" .. k] = number end
      end
      if #cells >= 2 and tonumber(cells[#cells]) then
        name, value = row, cells[#cells]
      end
    elseif not committed then
      name, value = line:gsub("#.*$", ""):match("^%s*([%w_%.%-/]+)%s+(%S+)%s*$")
    end
    if name then
      facts[name] = tonumber(value)
      if not facts[name] then
        fail(dir, needle, "claim data '" .. file .. "': '" .. name .. "' is not a number")
      end
    end
  end
  fact_files[file] = facts
  return facts
end

local comparisons = {
  ["<"] = function(a, b) return a < b end, ["<="] = function(a, b) return a <= b end,
  [">"] = function(a, b) return a > b end, [">="] = function(a, b) return a >= b end,
  ["=="] = function(a, b) return a == b end, ["!="] = function(a, b) return a ~= b end,
}

local function claim(span, dir)
  local text = plain(pandoc.utils.stringify(span.content))
  local file, check = span.attributes.data, span.attributes.check
  local needle = check or text
  if not file or not check then
    fail(dir, text, "a .claim span needs data=\"FILE\" and check=\"NAME OP VALUE\": '"
      .. text .. "'")
  end
  local facts = facts_of(dir, file, needle)
  local function value_of(token)
    local number = tonumber(token)
    if number then return number end
    if facts[token] ~= nil then return facts[token] end
    -- A product, e.g. 1.5*floor/affine_fixed#2, or tie_factor*floor/exact_double#2 (a
    -- factor that is itself a fact); what follows the * may be a sum.
    local factor, rest = token:match("^([^*+]+)%*(.+)$")
    if factor then return value_of(factor) * value_of(rest) end
    for at in token:gmatch("()%+") do -- a sum of facts, e.g. a#2+b#2
      local left, right = token:sub(1, at - 1), token:sub(at + 1)
      if (tonumber(left) or facts[left] ~= nil or left:find("[*+]"))
          and (tonumber(right) or facts[right] ~= nil or right:find("[*+]")) then
        return value_of(left) + value_of(right)
      end
    end
    if facts[token] == nil then
      fail(dir, needle, "claim '" .. text .. "' uses '" .. token .. "', which " .. file
        .. " does not define")
    end
    return facts[token]
  end
  for condition in (check .. ";"):gmatch("([^;]*);") do
    if condition:match("%S") then
      local left, op, right = condition:match("^%s*(%S+)%s*([<>=!]=?)%s*(%S+)%s*$")
      if not left or not comparisons[op] then
        fail(dir, needle, "claim '" .. text .. "': cannot read the check '" .. condition
          .. "'")
      end
      local a, b = value_of(left), value_of(right)
      if not comparisons[op](a, b) then
        fail(dir, needle, string.format("claim contradicted by %s: %s is false (%s = %s, "
          .. "%s = %s): '%s'", file, condition:gsub("^%s+", ""):gsub("%s+$", ""), left,
          tostring(a), right, tostring(b), text))
      end
    end
  end
  return span.content
end

local function fact(span, dir)
  local file, name = span.attributes.data, span.attributes.name
  if not file or not name then
    fail(dir, "{.fact", "a .fact span needs data=\"FILE\" and name=\"NAME\"")
  end
  local value = facts_of(dir, file, name)[name]
  if value == nil then
    fail(dir, name, "fact '" .. name .. "' is not in " .. file)
  end
  return pandoc.Str(string.format(span.attributes.format or "%g", value))
end

render_inlines = function(doc, dir_of_block)
  return doc:walk({
    Cite = function(cite)
      -- A key without a colon is a bibliography entry (book/references.bib): left for
      -- citeproc, which runs after this filter.
      if not cite.citations[1].id:find(":", 1, true) then return nil end
      local out = pandoc.List()
      for i, citation in ipairs(cite.citations) do
        if i > 1 then out:insert(pandoc.Str(", ")) end
        out:insert(reference(citation.id, dir_of_block()))
      end
      return out
    end,
    Span = function(span)
      if span.classes:includes("test") then return test_reference(span, dir_of_block()) end
      if span.classes:includes("index") then return index_term(span) end
      if span.classes:includes("claim") then return claim(span, dir_of_block()) end
      if span.classes:includes("fact") then return fact(span, dir_of_block()) end
    end,
  })
end

---------------------------------------------------------------------------------------

-- HTML: pandoc's MathML marks every parenthesis stretchy, so a browser grows "(x_k)" to
-- the height of its subscript and pads it. In TeX only \left, \right and \big... grow a
-- delimiter; make the MathML say the same.
local function fixed_delimiters(doc)
  if target ~= "html" then return doc end
  return doc:walk({
    Math = function(math)
      if math.text:find("\\left") or math.text:find("\\right") or math.text:find("\\[bB]ig")
          or math.text:find("\\middle") then
        return nil
      end
      local html = pandoc.write(pandoc.Pandoc({ pandoc.Plain({ math }) }), "html5",
                                { html_math_method = "mathml" })
      html = html:gsub('<mo stretchy="true" form="(%a+)">', '<mo stretchy="false" form="%1">')
      return pandoc.RawInline("html", (html:gsub("%s+$", "")))
    end,
  })
end

-- Tables in the PDF. Pandoc gives a pipe table whose lines are long columns in proportion
-- to its dashes ("|:--|--:|": all equal), and LaTeX then breaks a name such as
-- "subdivided-16 fixed" inside a narrow column. Size the columns from their text instead:
-- a table whose widest cells, heading included, fit the line gets natural widths (no
-- wrapping at all); otherwise each column gets its longest word, plus a share of the rest
-- of the line in proportion to how much longer its longest body cell is (headings may
-- wrap between words, names and numbers in the body should not), each word with two
-- characters to spare. Widths are in characters of the tables' \small face (about 4.6
-- pt each) on the 155 mm text block (439 pt), less 12 pt between columns.
-- book/latex/header.tex forbids breaking a word in a cell, and the PDF check fails on a
-- word wider than its column.
local table_line_pt, table_char_pt, table_gap_pt = 439, 4.6, 12
local function table_text_widths(tbl)
  local words, body, all = {}, {}, {}
  local function measure(row, in_body)
    for k, cell in ipairs(row.cells) do
      -- Math does not break: one word, with each TeX command counted as one character.
      local text = pandoc.utils.stringify(pandoc.List(cell.contents):map(function(block)
        return pandoc.walk_block(block, { Math = function(m)
          local shown = m.text:gsub("\\%a+", "x"):gsub("\\[ ,;]", "x")
          return pandoc.Str((shown:gsub("[%s{}_^$\\]", "")))
        end })
      end))
      local length = utf8.len(text) or #text
      all[k] = math.max(all[k] or 0, length)
      if in_body then body[k] = math.max(body[k] or 0, length) end
      for word in text:gmatch("%S+") do
        words[k] = math.max(words[k] or 0, utf8.len(word) or #word)
      end
    end
  end
  for _, row in ipairs(tbl.head.rows) do measure(row, false) end
  for _, b in ipairs(tbl.bodies) do
    for _, row in ipairs(b.head) do measure(row, false) end
    for _, row in ipairs(b.body) do measure(row, true) end
  end
  for _, row in ipairs(tbl.foot.rows) do measure(row, true) end
  return words, body, all
end

local function latex_table_widths(doc)
  if target ~= "latex" then return doc end
  return doc:walk({
    Table = function(tbl)
      local n = #tbl.colspecs
      local words, body, all = table_text_widths(tbl)
      local room = (table_line_pt - table_gap_pt * (n - 1)) / table_char_pt
      local sum_words, sum_body, sum_all = 0, 0, 0
      for k = 1, n do
        words[k] = (words[k] or 0) + 2 -- a little room: italic math and bold run wide
        body[k] = math.max((body[k] or 0) + 1, words[k])
        sum_words, sum_body = sum_words + words[k], sum_body + body[k]
        sum_all = sum_all + (all[k] or 0) + 1
      end
      local share = 0
      if sum_body > sum_words then
        share = math.min(1, math.max(0, (room - sum_words) / (sum_body - sum_words)))
      end
      local used = 0
      for k = 1, n do used = used + words[k] + (body[k] - words[k]) * share end
      for k = 1, n do
        local width = nil -- natural: the column as wide as its widest cell
        if sum_all > room then
          -- what is left of the line goes to the columns in proportion to their words
          local base = words[k] + (body[k] - words[k]) * share
          width = (base + math.max(0, room - used) * base / used) / math.max(room, used)
        end
        tbl.colspecs[k] = { tbl.colspecs[k][1], width }
      end
      return tbl
    end,
  })
end

-- A page that is not a chapter: references and named tests resolve, headings are not
-- numbered, and `::: contents` is filled with the table of contents.
-- `kit-points-per-mark: N` of book/metadata.yaml: what a mark is worth in a kit.
local points_per_mark
local function kit_points_per_mark()
  if not points_per_mark then
    local text = read_file(root .. "/book/metadata.yaml") or ""
    points_per_mark = tonumber(text:match("\nkit%-points%-per%-mark:%s*(%d+)") or "")
    if not points_per_mark then
      io.stderr:write("book/metadata.yaml: error: no line 'kit-points-per-mark: N'\n")
      os.exit(1)
    end
  end
  return points_per_mark
end
-- The exercise map (`::: exercise-map` on a page): every exercise of the book with its
-- kind, marks, difficulty, kit points (an exercise with a region) and the numbers of the
-- objectives it checks, read
-- from the tags (the one place that metadata lives), then the objectives that no
-- exercise checks, for the exam to cover.
local book_exercises = {} -- every exercise of the book, filled by exercise_map()
local function exercise_map()
  local rows, unchecked = {}, {}
  book_exercises = {}
  local per_mark = nil
  for _, dir in ipairs(all_chapters) do
    local text = read_file(root .. "/" .. chapter_file(dir))
    if text then
      local doc = pandoc.read(text, "markdown")
      local objectives, in_exercises, checked = {}, false, {}
      for _, block in ipairs(doc.blocks) do
        if block.t == "Div" and block.classes:includes("objectives") then
          for _, b in ipairs(block.content) do
            if b.t == "BulletList" then
              for _, item in ipairs(b.content) do
                objectives[#objectives + 1] = pandoc.utils.stringify(item)
              end
            end
          end
        elseif block.t == "Header" and block.level <= 2 then
          in_exercises = block.level == 2
            and pandoc.utils.stringify(block.content) == "Exercises"
        elseif in_exercises and block.t == "OrderedList" then
          for index, item in ipairs(block.content) do
            local first = item[1]
            local span = first and (first.t == "Para" or first.t == "Plain") and first.content[1]
            if span and span.t == "Span" and span.classes:includes("exercise") then
              local a = span.attributes
              local points = "–"
              if a.region then
                per_mark = per_mark or kit_points_per_mark()
                points = tostring((tonumber(a.marks or "") or 0) * per_mark)
              end
              for n in (a.objectives or ""):gmatch("%d+") do checked[tonumber(n)] = true end
              rows[#rows + 1] = { string.format("%d.%d", chapter_number(dir), index),
                a.kind or "?", a.marks or "?", a.difficulty or "?", points,
                ((a.objectives or ""):gsub(",", ", ")) }
              book_exercises[#book_exercises + 1] = { number = rows[#rows][1],
                kind = a.kind or "?", marks = tonumber(a.marks or "") or 0,
                region = a.region }
            end
          end
        end
      end
      for n, objective in ipairs(objectives) do
        if not checked[n] then
          unchecked[#unchecked + 1] = { string.format("%d, objective %d", chapter_number(dir), n),
                                        objective }
        end
      end
    end
  end
  local function cell(text) return { pandoc.Plain({ pandoc.Str(text) }) } end
  local body = {}
  for _, row in ipairs(rows) do
    local cells = {}
    for k, text in ipairs(row) do
      cells[k] = cell(text)
    end
    body[#body + 1] = cells
  end
  local headers = {}
  for k, text in ipairs({ "exercise", "kind", "marks", "difficulty", "kit points",
                          "objectives" }) do
    headers[k] = cell(text)
  end
  local aligns = { "AlignLeft", "AlignLeft", "AlignRight", "AlignLeft", "AlignRight",
                   "AlignLeft" }
  local out = { pandoc.utils.from_simple_table(pandoc.SimpleTable({}, aligns,
    { 0, 0, 0, 0, 0, 0 }, headers, body)) }
  if #unchecked > 0 then
    out[#out + 1] = pandoc.Para({ pandoc.Str("Objectives that no exercise checks (the exam "
      .. "questions cover them):") })
    local items = {}
    for _, u in ipairs(unchecked) do
      items[#items + 1] = { pandoc.Plain({ pandoc.Strong({ pandoc.Str("Chapter " .. u[1] .. ":") }),
                                          pandoc.Space(), pandoc.Str(u[2]) }) }
    end
    out[#out + 1] = pandoc.BulletList(items)
  end
  return out
end

-- A page's `::: solution` block (an exam question's worked answer, a rubric): kept,
-- headed "Answer.", in the teacher's edition only, as a chapter's solutions are.
local function page_solution(div)
  if os.getenv("EP_TEACHER") ~= "1" then return {} end
  local content = pandoc.List({ pandoc.Para({ pandoc.Strong({ pandoc.Str("Answer.") }) }) })
  content:extend(div.content)
  return { pandoc.Div(content, { class = "solution" }) }
end

-- A rubric, `::: {.rubric exercise="N.M"}` holding a list with one item per mark (what
-- earns it), for a written (derive or measure) exercise without a region. A page with
-- rubrics must have one for every such exercise of the book, each with as many items as
-- the exercise has marks; each is headed with the exercise's number, kind and marks.
local function check_rubrics(rubrics)
  exercise_map() -- fills book_exercises
  local wanted = {}
  for _, e in ipairs(book_exercises) do
    if e.kind ~= "implement" and not e.region then wanted[e.number] = e end
  end
  for number, rubric in pairs(rubrics) do
    local e = wanted[number]
    if not e then
      fail(nil, 'exercise="' .. number .. '"', "a rubric for exercise " .. number
        .. ", which is no derive or measure exercise without a region")
    end
    if rubric.items ~= e.marks then
      fail(nil, 'exercise="' .. number .. '"', string.format("the rubric of exercise %s has "
        .. "%d items, but the exercise has %d marks: one item per mark", number,
        rubric.items, e.marks))
    end
  end
  for _, e in ipairs(book_exercises) do
    if wanted[e.number] and not rubrics[e.number] then
      fail(nil, "{.rubric", "exercise " .. e.number .. " (" .. e.kind .. ", " .. e.marks
        .. " marks) has no rubric: add ::: {.rubric exercise=\"" .. e.number
        .. "\"} with one item per mark")
    end
  end
  return wanted
end

local function render_page(doc)
  local page_text = read_file(page_file) or ""
  refuse_fence_text(doc.blocks, function() return page_file, page_text end)
  doc = render_inlines(doc, function() return nil end)
  local rubrics = {}
  doc:walk({
    Div = function(div)
      if div.classes:includes("rubric") then
        local number = div.attributes.exercise or "?"
        if rubrics[number] then
          fail(nil, 'exercise="' .. number .. '"', "two rubrics for exercise " .. number)
        end
        local items = 0
        for _, b in ipairs(div.content) do
          if b.t == "BulletList" or b.t == "OrderedList" then items = items + #b.content end
        end
        rubrics[number] = { items = items }
      end
    end,
  })
  local rubric_exercises = next(rubrics) and check_rubrics(rubrics) or {}
  doc = doc:walk({
    Div = function(div)
      if div.classes:includes("contents") then
        div.content = { contents_list() }
        return div
      elseif div.classes:includes("exercise-map") then
        div.content = exercise_map()
        return div
      elseif div.classes:includes("solution") then
        return page_solution(div)
      elseif div.classes:includes("rubric") then
        local e = rubric_exercises[div.attributes.exercise or ""]
        local head = pandoc.Para({ pandoc.Strong({ pandoc.Str(string.format(
          "Exercise %s (%s, %d mark%s):", e.number, e.kind, e.marks, e.marks == 1 and "" or "s")) }) })
        local content = pandoc.List({ head })
        content:extend(div.content)
        div.content = content
        return div
      end
    end,
    CodeBlock = function(block)
      for _, class in ipairs(block.classes) do
        if allowed_code_classes[class] then return nil end
      end
      fail(nil, "```", "a code block typed by hand: mark it .pseudocode / .text / .sh / .toml")
    end,
  })
  return latex_table_widths(fixed_delimiters(doc))
end

local teacher = os.getenv("EP_TEACHER") == "1"

local exercise_kinds = { derive = true, implement = true, measure = true }
local difficulties = { easy = true, medium = true, hard = true }

-- The objective numbers of an exercise tag's objectives="1,3", each checked to name one
-- of the chapter's `objective_count` objectives.
local function exercise_objectives(span, dir, number, objective_count)
  local text = span.attributes.objectives or ""
  local numbers = {}
  for item in (text .. ","):gmatch("([^,]*),") do
    local n = tonumber(item:match("^%s*(%d+)%s*$") or "")
    if not n or n < 1 or n > objective_count then
      fail(dir, "{.exercise", string.format("exercise %d: objectives=\"%s\" must list the "
        .. "numbers (1 to %d) of the chapter's objectives it checks, e.g. objectives=\"1,3\"",
        number, text, objective_count))
    end
    numbers[#numbers + 1] = tostring(n)
  end
  return numbers
end

-- []{.exercise kind=K marks=N difficulty=D objectives="1,3" region=R} ->
-- "[K, N marks, D; M points in the kit; objectives 1, 3]", after checking each.
local function exercise_tag(span, dir, number, objective_count)
  local kind, marks = span.attributes.kind, tonumber(span.attributes.marks or "")
  if not exercise_kinds[kind or ""] then
    fail(dir, "{.exercise", string.format("exercise %d: kind must be derive, implement or "
      .. "measure, not '%s'", number, tostring(kind)))
  end
  if not marks or marks < 1 or marks > 3 or marks ~= math.floor(marks) then
    fail(dir, "{.exercise", string.format("exercise %d: marks (its difficulty) must be 1, 2 "
      .. "or 3, not '%s'", number, tostring(span.attributes.marks)))
  end
  local difficulty = span.attributes.difficulty
  if not difficulties[difficulty or ""] then
    fail(dir, "{.exercise", string.format("exercise %d: difficulty must be easy, medium or "
      .. "hard, not '%s'", number, tostring(difficulty)))
  end
  local objectives = exercise_objectives(span, dir, number, objective_count)
  local text = string.format("[%s, %d mark%s, %s", kind, marks, marks == 1 and "" or "s",
                             difficulty)
  if span.attributes.region then
    -- What the chapter's kit gives for it: `make-kit check` (test kits_points) proves
    -- that the tests naming the region declare exactly this many points.
    text = text .. string.format("; %d points in the kit", marks * kit_points_per_mark())
  end
  text = text .. string.format("; objective%s %s", #objectives == 1 and "" or "s",
                               table.concat(objectives, ", "))
  return pandoc.Span({ pandoc.Strong({ pandoc.Str(text .. "]") }) }, { class = "exercise-tag" })
end

-- A solution: dropped (student book) or headed "Solution." (teacher's edition).
local function solution_blocks(div)
  if not teacher then return {} end
  local content = pandoc.List({ pandoc.Para({ pandoc.Strong({ pandoc.Str("Solution.") }) }) })
  content:extend(div.content)
  return { pandoc.Div(content, { class = "solution" }) }
end

-- Checks and renders the objectives, the summary, the exercises' tags and the solutions
-- of every chapter in `blocks` (top level, level-1 headings start chapters). The summary
-- (`::: summary`, "In short") stands directly before `## Exercises`: a chapter with
-- exercises has exactly one, and a summary anywhere else is an error.
local function teaching(blocks, dirs)
  local out, h1, dir = pandoc.List(), 0, nil
  local objectives, in_sections, in_exercises = 0, false, false
  local objective_count = 0 -- items of the chapter's objectives list
  local summary_waiting = false -- the block before this one was the summary
  local function finish()
    if dir and objectives ~= 1 then
      fail(dir, "# ", string.format("the chapter needs exactly one `::: objectives` block "
        .. "(what the reader will be able to do) before its first section, found %d",
        objectives))
    end
    if dir and summary_waiting then
      fail(dir, "::: summary", "the `::: summary` block must stand directly before "
        .. "`## Exercises`")
    end
  end
  for _, block in ipairs(blocks) do
    local keep = { block }
    local is_exercises = block.t == "Header" and block.level == 2
      and pandoc.utils.stringify(block.content) == "Exercises"
    if summary_waiting and not is_exercises then
      fail(dir, "::: summary", "the `::: summary` block must stand directly before "
        .. "`## Exercises`")
    end
    if is_exercises and not summary_waiting then
      fail(dir, "## Exercises", "the chapter needs a `::: summary` block (\"In short\": "
        .. "what was derived, the tests that prove it, the numbers that matter) directly "
        .. "before `## Exercises`")
    end
    summary_waiting = false
    if block.t == "Header" and block.level == 1 then
      finish()
      h1 = h1 + 1
      dir, objectives, in_sections, in_exercises = dirs[h1], 0, false, false
      objective_count = 0
    elseif block.t == "Header" and block.level == 2 then
      in_sections = true
      in_exercises = is_exercises
    elseif block.t == "Div" and block.classes:includes("summary") then
      if in_exercises then
        fail(dir, "::: summary", "the `::: summary` block must stand directly before "
          .. "`## Exercises`")
      end
      summary_waiting = true
    elseif block.t == "Div" and block.classes:includes("objectives") then
      if in_sections then
        fail(dir, "::: objectives", "the objectives block must come before the first section")
      end
      objectives = objectives + 1
      local content = pandoc.List({ pandoc.Para({ pandoc.Strong({
        pandoc.Str("After this chapter you will be able to:") }) }) })
      -- Numbered, as the exercises' tags name them ("objectives 1, 3").
      for _, b in ipairs(block.content) do
        if b.t == "BulletList" then
          objective_count = objective_count + #b.content
          content:insert(pandoc.OrderedList(b.content))
        else
          content:insert(b)
        end
      end
      keep = { pandoc.Div(content, { class = "objectives" }) }
    elseif block.t == "Div" and block.classes:includes("solution") then
      if not in_exercises then
        fail(dir, "::: solution", "a solution block outside the Exercises section")
      end
      keep = solution_blocks(block)
    elseif in_exercises and block.t == "OrderedList" then
      for number, item in ipairs(block.content) do
        local first = item[1]
        local span = first and (first.t == "Para" or first.t == "Plain") and first.content[1]
        if not (span and span.t == "Span" and span.classes:includes("exercise")) then
          fail(dir, "## Exercises", string.format("exercise %d does not begin with "
            .. "[]{.exercise kind=derive|implement|measure marks=1|2|3 "
            .. "difficulty=easy|medium|hard objectives=\"N,...\"}", number))
        end
        first.content[1] = exercise_tag(span, dir, number, objective_count)
        local kept = pandoc.List()
        for _, b in ipairs(item) do
          if b.t == "Div" and b.classes:includes("solution") then
            kept:extend(solution_blocks(b))
          else
            kept:insert(b)
          end
        end
        block.content[number] = kept
      end
    end
    out:extend(keep)
  end
  finish()
  return out
end

function Pandoc(doc)
  collect_labels()
  doc.blocks = for_this_edition(doc.blocks)
  if page_file then return render_page(doc) end
  -- Before the student book drops the solutions, so that both editions are checked.
  local h1_seen, texts = 0, {}
  refuse_fence_text(doc.blocks, function(block)
    if block.t == "Header" and block.level == 1 then h1_seen = h1_seen + 1 end
    local dir = chapters_here[math.max(h1_seen, 1)] or "??"
    texts[dir] = texts[dir] or read_file(root .. "/" .. chapter_file(dir)) or ""
    return chapter_file(dir), texts[dir]
  end)
  doc.blocks = teaching(doc.blocks, chapters_here)
  -- Inline references need the chapter each block belongs to: resolve them block by
  -- block, top level, tracking level-1 headings.
  local h1, blocks = 0, pandoc.List()
  for _, block in ipairs(doc.blocks) do
    if block.t == "Header" and block.level == 1 then h1 = h1 + 1 end
    local dir = chapters_here[math.max(h1, 1)]
    local single = pandoc.Pandoc({ block })
    single = render_inlines(single, function() return dir end)
    for _, b in ipairs(single.blocks) do blocks:insert(b) end
  end
  local state = { h1 = 0, dirs = chapters_here }
  doc.blocks = render_blocks(blocks, nil, state)
  if state.h1 ~= #chapters_here then
    error(string.format("expected %d chapter headings, found %d", #chapters_here, state.h1), 0)
  end
  if target == "html" and state.title then
    doc.meta.pagetitle = state.title
  end
  return latex_table_widths(fixed_delimiters(doc))
end
