-- live.lua: the HTML book's live figures (web/live.js, the library compiled to
-- WebAssembly by web/CMakeLists.txt). Runs before exactpixels.lua. A chapter marks one
-- with a fenced div right after the static figure it extends:
--
--   ::: {.live figure="ch02-fill-rule"}
--   Drag a vertex ... (the caption: HTML only)
--   :::
--
-- In HTML the div becomes a <figure data-live="loading" data-figure="NAME" hidden> that
-- live.js draws, unhides and marks data-live="ready"; the page then loads the module and
-- live.js once, at its end. Everywhere else (the PDF) the div and its caption are
-- dropped: the static figure stands, and no sentence there asks the reader to drag.
local target = os.getenv("EP_TARGET") or "html"
local any = false

local function live_figure(div)
  if not div.classes:includes("live") then return nil end
  local name = div.attributes["figure"]
  if not name or not name:match("^ch%d%d%-[%w%-]+$") then
    io.stderr:write("error: a .live div needs figure=\"chNN-name\" (found '" ..
      tostring(name) .. "')\n")
    os.exit(1)
  end
  if target ~= "html" then return {} end
  any = true
  local caption = pandoc.write(pandoc.Pandoc(div.content), "html")
  return pandoc.RawBlock("html", string.format(
    '<figure class="live-figure" id="live-%s" data-figure="%s" data-live="loading" hidden>\n'
    .. '<div class="live-stage"></div>\n'
    .. '<p class="live-state" role="status" aria-live="polite"></p>\n'
    .. '<figcaption>%s</figcaption>\n</figure>', name, name, caption))
end

local function scripts(doc)
  if any then
    doc.blocks:insert(pandoc.RawBlock("html",
      '<script src="live/exactpixels-live.js"></script>\n<script src="live/live.js"></script>'))
  end
  return doc
end

return { { Div = live_figure }, { Pandoc = scripts } }
