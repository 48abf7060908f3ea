// page_check.js: evaluated by the browser check (tests/bookcheck_html.cpp) in every page
// of the built book, after the page and its fonts have loaded. It only looks; the C++
// side decides what is wrong. Its value is an object:
//   links     every href (a, link) as an absolute URL, with its text
//   images    every <img>: its URL and whether it decoded to a non-empty picture
//   ids       every id and <a name> of the page (targets of #anchors)
//   rawTex    prose that still holds TeX: $$, \(, \[, \command, or pandoc's fallback
//             <span class="math"> (MathML conversion failed)
//   mathErrors every MathML <merror>, and every <math> the browser laid out with no size
//   wide      every listing (<pre>) or display equation whose content is wider than its
//             box (scrollWidth > clientWidth): the reader would have to scroll
//   tall       every display equation whose content is taller than its box
//             (scrollHeight > clientHeight): a vertical scroll bar, or a clipped formula
//   wrapped    every table cell whose text is one word (no space) laid out on more than
//             one line: a name or number broken inside itself
//   unnumbered on a chapter page (its <h1> carries a section number), every <h2> that
//             has none, such as an Exercises heading left unnumbered
//   fences    prose (not code) with a line that begins with ::: or ```: a Markdown fence
//             that was not read as one and reached the reader as text
(() => {
  const short = (text) => text.replace(/\s+/g, " ").trim().slice(0, 80);
  const links = [...document.querySelectorAll("a[href], link[href]")].map((a) => ({
    url: a.href,
    text: short(a.textContent || a.getAttribute("rel") || ""),
  }));
  const images = [...document.querySelectorAll("img")].map((img) => ({
    url: img.src,
    ok: img.complete && img.naturalWidth > 0 && img.naturalHeight > 0,
  }));
  const ids = [...document.querySelectorAll("[id]")].map((e) => e.id)
    .concat([...document.querySelectorAll("a[name]")].map((e) => e.name));

  // Prose only: code, listings, scripts and MathML may legitimately hold backslashes.
  const rawTex = [];
  const skip = "PRE, CODE, SCRIPT, STYLE, MATH, TEXTAREA";
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  const tex = /\$\$|\\\(|\\\[|\\[A-Za-z]{2,}|\$[^$\s][^$]*\$/;
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    const parent = node.parentElement;
    if (parent && !parent.closest(skip) && tex.test(node.nodeValue)) {
      rawTex.push(short(node.nodeValue));
    }
  }
  for (const span of document.querySelectorAll("span.math")) {
    rawTex.push("unrendered math: " + short(span.textContent));
  }

  // Fence text: a line of prose beginning with ::: or ```. A block's prose runs over
  // several nodes (links, emphasis); code and math in it are not prose, and a block
  // nested in it is checked on its own.
  const fences = [];
  const fence = /^\s*(:::|```)/;
  const notProse = "pre, code, script, style, math, svg, textarea";
  const blockTags = "p, li, div, table, ul, ol, dl, dt, dd, blockquote, figure, " +
    "figcaption, h1, h2, h3, h4, h5, h6, td, th";
  const proseOf = (node) => {
    if (node.nodeType === Node.TEXT_NODE) {
      return node.nodeValue;
    }
    if (node.nodeType !== Node.ELEMENT_NODE) {
      return "";
    }
    if (node.matches(notProse)) {
      return "\u2026"; // code or math in the line: shown as an ellipsis, not read
    }
    if (node.matches(blockTags)) {
      return "\n";
    }
    return [...node.childNodes].map(proseOf).join("");
  };
  for (const block of document.querySelectorAll(blockTags)) {
    if (block.closest(notProse)) {
      continue;
    }
    const text = [...block.childNodes].map(proseOf).join("");
    for (const line of text.split("\n")) {
      if (fence.test(line)) {
        fences.push(short(line));
      }
    }
  }

  const mathErrors = [];
  for (const e of document.querySelectorAll("merror")) {
    mathErrors.push("<merror>: " + short(e.textContent));
  }
  for (const m of document.querySelectorAll("math")) {
    const box = m.getBoundingClientRect();
    if (box.width === 0 || box.height === 0) {
      mathErrors.push("math laid out with no size: " + short(m.textContent));
    }
  }

  const wide = [];
  const boxes = document.querySelectorAll("pre, .equation > p:first-child");
  for (const box of boxes) {
    if (box.scrollWidth > box.clientWidth + 1) {
      wide.push({
        what: box.tagName === "PRE" ? "listing" : "equation",
        text: short((box.textContent || "").split("\n").find((l) => l.trim()) || ""),
        scroll: box.scrollWidth,
        client: box.clientWidth,
      });
    }
  }
  const tall = [];
  for (const box of document.querySelectorAll(".equation > p:first-child")) {
    if (box.scrollHeight > box.clientHeight + 1) {
      tall.push({
        text: short(box.textContent || ""),
        scroll: box.scrollHeight,
        client: box.clientHeight,
      });
    }
  }

  // A cell's lines: the distinct tops of the boxes its text is laid out in.
  const wrapped = [];
  for (const cell of document.querySelectorAll("td, th")) {
    const text = (cell.textContent || "").trim();
    if (text === "" || /\s/.test(text)) {
      continue;
    }
    const range = document.createRange();
    range.selectNodeContents(cell);
    const tops = new Set();
    for (const rect of range.getClientRects()) {
      if (rect.width > 0 && rect.height > 0) {
        tops.add(Math.round(rect.top));
      }
    }
    // A new line starts more than half a line below the last one (a sub- or superscript
    // in the same line is shifted by less).
    const style = getComputedStyle(cell);
    const lineHeight = parseFloat(style.lineHeight) || 1.2 * parseFloat(style.fontSize);
    let lines = 0;
    let last = -Infinity;
    for (const top of [...tops].sort((a, b) => a - b)) {
      if (top - last > 0.6 * lineHeight) {
        ++lines;
        last = top;
      }
    }
    if (lines > 1) {
      wrapped.push({ text: short(text), lines });
    }
  }

  const unnumbered = [];
  if (document.querySelector("h1 .secnum")) {
    for (const h of document.querySelectorAll("h2")) {
      if (!h.querySelector(".secnum")) {
        unnumbered.push(short(h.textContent || ""));
      }
    }
  }
  return { links, images, ids, rawTex, mathErrors, wide, tall, wrapped, unnumbered, fences };
})()
