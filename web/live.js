// live.js: the HTML book's live figures. Each <figure data-live="loading"
// data-figure="NAME"> that the book's filter inserted (book/filters/live.lua) is drawn
// here as SVG and recomputed, whenever the reader moves something, by the library itself:
// the WebAssembly module web/live_figures.cpp, which exactpixels-live.js holds as base64
// (a page opened from file:// may not fetch a file, but may run a classic script).
// This file draws and reads input only; every covered pixel, tie, rule and texel shown
// is what the module answered. Once the module is loaded each figure's data-live becomes
// "ready" and its data-state holds what it shows, as JSON (the interactive tests read it).
//
// Every handle is a focusable SVG element: drag it with the mouse (or a finger), or
// focus it (Tab) and move it with the arrow keys (with Shift: larger steps).
"use strict";

(function () {
  const SVG = "http://www.w3.org/2000/svg";
  const CELL = 40; // screen pixels per book pixel

  function el(name, attributes, parent) {
    const node = document.createElementNS(SVG, name);
    for (const [key, value] of Object.entries(attributes || {})) {
      node.setAttribute(key, value);
    }
    if (parent) parent.appendChild(node);
    return node;
  }

  function decode(base64) {
    const text = atob(base64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return bytes;
  }

  // The module needs no system: its WASI imports (left over from the C library's
  // start-up code) are never called by the figures' functions; each one fails loudly.
  function wasiStubs() {
    const names = ["environ_get", "environ_sizes_get", "fd_close", "fd_seek", "fd_write",
                   "proc_exit"];
    const stubs = {};
    for (const name of names) {
      stubs[name] = () => { throw new Error("live figures: unexpected WASI call " + name); };
    }
    return new Proxy(stubs, {
      get: (target, name) => target[name] ||
        (() => { throw new Error("live figures: unexpected WASI call " + String(name)); }),
    });
  }

  async function loadModule() {
    const bytes = decode(window.exactpixelsModule);
    const { instance } = await WebAssembly.instantiate(bytes,
      { wasi_snapshot_preview1: wasiStubs() });
    instance.exports._initialize();
    const e = { ...instance.exports };
    // The cells array, read through a fresh view after every call (memory may grow).
    e.cells = (count) => new Int32Array(e.memory.buffer, e.ep_cells(), count);
    return e;
  }

  // A draggable, focusable handle at (x, y) in book units, drawn in `parent` at
  // (x, y) * scale * CELL. onMove() sees the new position, already on the handle's grid
  // (step) and inside bounds; it returns false to refuse it.
  function handle(parent, label, state, step, bounds, onMove, scale = 1) {
    const node = el("circle", { r: 9, class: "live-handle", tabindex: 0, role: "slider",
                                "aria-label": label }, parent);
    const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
    const snap = (v) => Math.round(v / step) * step;
    function place() {
      node.setAttribute("cx", state.x * scale * CELL);
      node.setAttribute("cy", state.y * scale * CELL);
      node.setAttribute("aria-valuetext", `${label} at (${state.x}, ${state.y})`);
    }
    function moveTo(x, y) {
      x = clamp(snap(x), bounds.x0, bounds.x1);
      y = clamp(snap(y), bounds.y0, bounds.y1);
      if (x === state.x && y === state.y) return;
      const old = { x: state.x, y: state.y };
      state.x = x;
      state.y = y;
      if (onMove() === false) {
        state.x = old.x;
        state.y = old.y;
      }
      place();
    }
    function toBook(event) {
      const p = new DOMPoint(event.clientX, event.clientY)
        .matrixTransform(parent.getScreenCTM().inverse());
      return { x: p.x / (scale * CELL), y: p.y / (scale * CELL) };
    }
    node.addEventListener("pointerdown", (event) => {
      event.preventDefault();
      node.focus();
      node.classList.add("dragging");
      const move = (e) => { const p = toBook(e); moveTo(p.x, p.y); };
      const up = () => {
        node.classList.remove("dragging");
        window.removeEventListener("pointermove", move);
        window.removeEventListener("pointerup", up);
      };
      window.addEventListener("pointermove", move);
      window.addEventListener("pointerup", up);
    });
    node.addEventListener("keydown", (event) => {
      const big = event.shiftKey ? bounds.bigStep || 1 : step;
      const moves = { ArrowLeft: [-big, 0], ArrowRight: [big, 0],
                      ArrowUp: [0, -big], ArrowDown: [0, big] };
      const d = moves[event.key];
      if (!d) return;
      event.preventDefault();
      moveTo(state.x + d[0], state.y + d[1]);
    });
    place();
    return node;
  }

  // Handles for a triangle's vertices in a W x H grid: steps of 1/8 px, Shift for 1 px.
  function vertexHandles(svg, v, W, H, update) {
    const bounds = { x0: 0, y0: 0, x1: W, y1: H, bigStep: 1 };
    v.forEach((p, i) => handle(svg, `vertex v${i}`, p, 1 / 8, bounds, update));
  }

  function grid(svg, width, height) {
    const g = el("g", { class: "live-grid" }, svg);
    for (let x = 0; x <= width; ++x) {
      el("line", { x1: x * CELL, y1: 0, x2: x * CELL, y2: height * CELL }, g);
    }
    for (let y = 0; y <= height; ++y) {
      el("line", { x1: 0, y1: y * CELL, x2: width * CELL, y2: y * CELL }, g);
    }
    return g;
  }

  function newSvg(figure, width, height, margin) {
    const m = margin * CELL;
    const w = width * CELL + 2 * m, h = height * CELL + 2 * m; // CSS pixels, at most
    return el("svg", { viewBox: `${-m} ${-m} ${w} ${h}`, width: w, height: h,
                       class: "live-svg", role: "group",
                       "aria-label": figure.dataset.figure },
              figure.querySelector(".live-stage"));
  }

  function show(figure, state, line) {
    figure.dataset.state = JSON.stringify(state);
    figure.querySelector(".live-state").textContent = line;
  }

  const fmt = (v) => String(v);
  const point = (p) => `(${fmt(p.x)}, ${fmt(p.y)})`;

  // Chapter 1: the scanline walk and the gradient of c = 0, 1, 1/2 at the vertices.
  function scanline(figure, m) {
    const W = 12, H = 9;
    const v = [{ x: 4.25, y: 0.625 }, { x: 11.25, y: 3.875 }, { x: 1.375, y: 8.25 }];
    const svg = newSvg(figure, W, H, 0.4);
    const cellLayer = el("g", {}, svg);
    grid(svg, W, H);
    const outline = el("polygon", { class: "live-triangle" }, svg);
    const arrows = el("g", {}, svg);
    const n = (x) => Number(x.toPrecision(6));
    function update() {
      const covered = m.ep_scanline(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y, W, H);
      if (covered < 0) return false;
      const cells = m.cells(2 * H);
      const g = new Float64Array(m.memory.buffer, m.ep_values(), 4);
      cellLayer.replaceChildren();
      const spans = [];
      for (let y = 0; y < H; ++y) {
        const x0 = cells[2 * y], x1 = cells[2 * y + 1];
        if (x0 < 0) continue;
        spans.push([y, x0, x1]);
        el("rect", { x: x0 * CELL, y: y * CELL, width: (x1 - x0) * CELL, height: CELL,
                     class: "live-covered" }, cellLayer);
      }
      outline.setAttribute("points", v.map((p) => `${p.x * CELL},${p.y * CELL}`).join(" "));
      // The gradient, drawn from the centroid: 30 px of the figure per unit of c per px.
      arrows.replaceChildren();
      const cx = (v[0].x + v[1].x + v[2].x) / 3, cy = (v[0].y + v[1].y + v[2].y) / 3;
      el("line", { x1: cx * CELL, y1: cy * CELL, x2: (cx + 30 * g[0]) * CELL,
                   y2: (cy + 30 * g[1]) * CELL, class: "live-edge live-gradient" }, arrows);
      const gradient = { closedForm: [g[0], g[1]], splitEdge: [g[2], g[3]] };
      show(figure, { vertices: v.map((p) => [p.x, p.y]), covered, spans, ...gradient },
           `v0 ${point(v[0])} (c = 0), v1 ${point(v[1])} (c = 1), v2 ${point(v[2])} ` +
           `(c = 1/2): ${spans.length} spans, ${covered} pixels covered; gradient ` +
           `(dc/dx, dc/dy) closed form (${n(g[0])}, ${n(g[1])}), split edge ` +
           `(${n(g[2])}, ${n(g[3])}).`);
      return true;
    }
    vertexHandles(svg, v, W, H, update);
    update();
  }

  // Chapter 2: the fill rule on a triangle whose vertices snap to the sub-pixel grid.
  function fillRule(figure, m) {
    const W = 8, H = 7;
    const v = [{ x: 0.5, y: 0.5 }, { x: 5.5, y: 0.5 }, { x: 5.5, y: 5.5 }];
    const svg = newSvg(figure, W, H, 0.4);
    const cellLayer = el("g", {}, svg);
    grid(svg, W, H);
    const centres = el("g", {}, svg);
    const outline = el("polygon", { class: "live-triangle" }, svg);
    const edgeNames = ["v1 to v2", "v2 to v0", "v0 to v1"];
    function update() {
      const covered = m.ep_fill_rule(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y, W, H);
      if (covered < 0) return false;
      const cells = m.cells(W * H);
      cellLayer.replaceChildren();
      centres.replaceChildren();
      const pixels = [];
      let won = 0, lost = 0;
      for (let y = 0; y < H; ++y) {
        for (let x = 0; x < W; ++x) {
          const c = cells[y * W + x];
          const isCovered = (c & 1) !== 0;
          const tie = (c >> 1) & 3;
          if (isCovered) {
            pixels.push([x, y]);
            el("rect", { x: x * CELL, y: y * CELL, width: CELL, height: CELL,
                         class: "live-covered" }, cellLayer);
          }
          el("circle", { cx: (x + 0.5) * CELL, cy: (y + 0.5) * CELL, r: tie ? 5 : 2.5,
                         class: tie ? (isCovered ? "live-tie-won" : "live-tie-lost")
                                    : "live-centre" }, centres);
          if (tie) {
            isCovered ? ++won : ++lost;
            const t = el("text", { x: (x + 0.5) * CELL + 7, y: (y + 0.5) * CELL - 6,
                                   class: "live-label" }, centres);
            t.textContent = `e${tie - 1}`;
          }
        }
      }
      const topLeft = [0, 1, 2].map((i) => (cells[0] >> (3 + i) & 1) === 1);
      outline.setAttribute("points", v.map((p) => `${p.x * CELL},${p.y * CELL}`).join(" "));
      const edges = topLeft.map((t, i) => `e${i} (${edgeNames[i]}) ${t ? "top or left" : "bottom or right"}`);
      show(figure, { vertices: v.map((p) => [p.x, p.y]), covered, pixels, tiesWon: won,
                     tiesLost: lost, topLeft },
           `v0 ${point(v[0])}, v1 ${point(v[1])}, v2 ${point(v[2])}: ${covered} pixels ` +
           `covered; ${won} centres on an edge won (by a top or left edge), ${lost} lost ` +
           `(to a bottom or right edge). ${edges.join("; ")}.`);
      return true;
    }
    vertexHandles(svg, v, W, H, update);
    update();
  }

  // Chapter 0: which pixel centres an edge between whole-pixel points goes through.
  function edgeCentres(figure, m) {
    const W = 12, H = 8;
    const a = { x: 1, y: 1 }, b = { x: 5, y: 7 };
    const svg = newSvg(figure, W, H, 0.4);
    grid(svg, W, H);
    const centres = el("g", {}, svg);
    const line = el("line", { class: "live-edge" }, svg);
    function update() {
      const count = m.ep_edge_centres(a.x, a.y, b.x, b.y, W, H);
      if (count < 0) return false;
      const cells = m.cells(W * H + 2);
      const twos = [cells[W * H], cells[W * H + 1]];
      centres.replaceChildren();
      const on = [];
      for (let y = 0; y < H; ++y) {
        for (let x = 0; x < W; ++x) {
          const hit = cells[y * W + x] === 1;
          if (hit) on.push([x, y]);
          el("circle", { cx: (x + 0.5) * CELL, cy: (y + 0.5) * CELL, r: hit ? 6 : 2.5,
                         class: hit ? "live-tie-won" : "live-centre" }, centres);
        }
      }
      line.setAttribute("x1", a.x * CELL); line.setAttribute("y1", a.y * CELL);
      line.setAttribute("x2", b.x * CELL); line.setAttribute("y2", b.y * CELL);
      const dx = b.x - a.x, dy = b.y - a.y;
      const powers = dx && dy ? `; the largest powers of two dividing them are 2^${twos[0]} and 2^${twos[1]}` : "";
      show(figure, { a: [a.x, a.y], b: [b.x, b.y], count, centres: on, twos },
           `Edge from ${point(a)} to ${point(b)}, dx = ${dx}, dy = ${dy}${powers}: ` +
           `it goes through ${count} pixel centre${count === 1 ? "" : "s"}.`);
      return true;
    }
    const bounds = { x0: 0, y0: 0, x1: W, y1: H, bigStep: 2 };
    handle(svg, "edge start", a, 1, bounds, update);
    handle(svg, "edge end", b, 1, bounds, update);
    update();
  }

  // Chapter 4: the texture direction turned, the rule chosen from the sign of BC - AD.
  function texelRule(figure, m) {
    const N = 8;
    const g = { x: -1, y: 0 };     // (dc/dx, dc/dy): the handle, on a 1/4 grid
    const depth = { x: 0, y: 0 };  // dq/dx: the second handle, on a 1/32 grid
    const R = 2;                   // the gradient dial reaches +-2
    const svg = newSvg(figure, N + 7, 5, 0.4);
    // The row of pixel centres, their u and texels.
    const row = el("g", {}, svg);
    // The dial for the gradient, to the right of the row: centre (N + 3.5, 2.5).
    const dial = el("g", { transform: `translate(${(N + 3.5) * CELL},${2.5 * CELL})` }, svg);
    el("circle", { r: R * CELL * 0.5, class: "live-dial" }, dial);
    el("line", { x1: -R * CELL * 0.5, y1: 0, x2: R * CELL * 0.5, y2: 0, class: "live-axis" }, dial);
    el("line", { x1: 0, y1: -R * CELL * 0.5, x2: 0, y2: R * CELL * 0.5, class: "live-axis" }, dial);
    const arrow = el("line", { class: "live-edge" }, dial);
    // The depth slider under the row: dq/dx from -1/4 to 1/4.
    const slider = el("g", { transform: `translate(${N * CELL * 0.5},${4.3 * CELL})` }, svg);
    el("line", { x1: -0.25 * 8 * CELL, y1: 0, x2: 0.25 * 8 * CELL, y2: 0, class: "live-axis" }, slider);
    function update() {
      if (m.ep_texel_rule(g.x, g.y, depth.x, N) < 0) return false;
      const cells = m.cells(3 + 2 * N);
      const rule = cells[0], sign = cells[1], signY = cells[2];
      row.replaceChildren();
      const texels = [], rule1 = [];
      for (let a = 0; a < N; ++a) {
        const t = cells[3 + 2 * a], t1 = cells[4 + 2 * a];
        texels.push(t === 9999 ? null : t);
        rule1.push(t1 === 9999 ? null : t1);
        el("rect", { x: a * CELL, y: 1 * CELL, width: CELL, height: CELL,
                     class: t === 9999 ? "live-centre" : (t < 0 || t > 7 ? "live-tie-lost" : "live-covered") }, row);
        el("circle", { cx: (a + 0.5) * CELL, cy: 1.5 * CELL, r: 2.5, class: "live-centre" }, row);
        const label = el("text", { x: (a + 0.5) * CELL, y: 0.8 * CELL, class: "live-label live-middle" }, row);
        label.textContent = t === 9999 ? "-" : String(t);
        const label1 = el("text", { x: (a + 0.5) * CELL, y: 2.6 * CELL,
                                    class: "live-label live-middle" + (t1 !== t ? " live-differs" : "") }, row);
        label1.textContent = t1 === 9999 ? "-" : String(t1);
      }
      const rowLabel = el("text", { x: N * CELL + 6, y: 0.8 * CELL, class: "live-label" }, row);
      rowLabel.textContent = `rule ${rule}`;
      const row1Label = el("text", { x: N * CELL + 6, y: 2.6 * CELL, class: "live-label" }, row);
      row1Label.textContent = "rule 1";
      el("rect", { x: 0, y: CELL, width: N * CELL, height: CELL, class: "live-outline" }, row);
      arrow.setAttribute("x1", 0); arrow.setAttribute("y1", 0);
      arrow.setAttribute("x2", g.x * CELL * 0.5); arrow.setAttribute("y2", g.y * CELL * 0.5);
      const names = { "-1": "negative", "0": "zero", "1": "positive" };
      show(figure, { dcdx: g.x, dcdy: g.y, dqdx: depth.x, rule, numeratorSign: sign,
                     numeratorYSign: signY, texels, rule1 },
           `dc/dx = ${g.x}, dc/dy = ${g.y}, d(1/w)/dx = ${depth.x}: BC - AD is ` +
           `${names[sign]}` + (sign === 0 ? ` (dc/dy's numerator ${names[signY]})` : "") +
           `, so rule ${rule}; texels ${texels.map((t) => t === null ? "-" : t).join(" ")}` +
           ` (rule 1 alone: ${rule1.map((t) => t === null ? "-" : t).join(" ")}).`);
      return true;
    }
    // The gradient handle: one unit of dc/dx is half a pixel of the dial.
    const gBounds = { x0: -R, y0: -R, x1: R, y1: R, bigStep: 1 };
    handle(dial, "texture direction", g, 1 / 4, gBounds, update, 0.5);
    const dBounds = { x0: -0.25, y0: 0, x1: 0.25, y1: 0, bigStep: 1 / 8 };
    handle(slider, "depth slope", depth, 1 / 32, dBounds, update, 8);
    update();
  }

  // Chapter 3: u along one span by each mapper, as the depth ratio grows.
  function spanMappers(figure, m) {
    const K = 64, SX = 6, SY = 4;  // SVG units per pixel and per texel
    const r = { x: 4, y: 0 };      // the depth ratio: the slider, on a 1/4 grid
    const svg = newSvg(figure, (K * SX) / CELL + 0.5, (64 * SY) / CELL + 1.6, 0.4);
    const names = ["exact", "affine", "quadratic", "subdivided (N = 16)"];
    const plot = el("g", {}, svg);
    el("rect", { x: 0, y: 0, width: K * SX, height: 64 * SY, class: "live-outline" }, svg);
    const lines = names.map((_, i) => el("polyline", { class: `live-mapper live-mapper-${i}` }, plot));
    const legend = el("g", {}, svg);
    names.forEach((name, i) => {
      el("line", { x1: 8, y1: 14 + 16 * i, x2: 28, y2: 14 + 16 * i, class: `live-mapper live-mapper-${i}` }, legend);
      el("text", { x: 34, y: 18 + 16 * i, class: "live-label" }, legend).textContent = name;
    });
    // The slider under the plot: r from 1 to 16, 16 SVG units per unit of r.
    const slider = el("g", { transform: `translate(${-16},${64 * SY + 40})` }, svg);
    el("line", { x1: 16, y1: 0, x2: 16 * 16, y2: 0, class: "live-axis" }, slider);
    const rLabel = el("text", { x: 16 * 16 + 14, y: 5, class: "live-label" }, slider);
    function update() {
      if (m.ep_span_mappers(r.x) < 0) return false;
      const u = new Float64Array(m.memory.buffer, m.ep_values(), 4 * K + 4);
      const other = m.cells(4);
      const worst = [], differing = [];
      lines.forEach((line, i) => {
        const points = [];
        for (let k = 0; k < K; ++k) {
          points.push(`${(k + 0.5) * SX},${(64 - Math.max(-4, Math.min(68, u[i * K + k]))) * SY}`);
        }
        line.setAttribute("points", points.join(" "));
        worst.push(u[4 * K + i]);
        differing.push(other[i]);
      });
      rLabel.textContent = `r = ${r.x}`;
      const parts = [1, 2, 3].map((i) => `${names[i]} ${worst[i].toFixed(3)} (${differing[i]} pixels on another texel)`);
      show(figure, { ratio: r.x, worst, differing },
           `Depth ratio r = ${r.x}; the largest distance from the exact u, in texels: ` +
           `${parts.join(", ")}.`);
      return true;
    }
    handle(slider, "depth ratio", r, 1 / 4, { x0: 1, y0: 0, x1: 16, y1: 0, bigStep: 1 },
           update, 16 / CELL);
    update();
  }

  const figures = { "ch00-edge-centres": edgeCentres, "ch01-scanline": scanline, "ch02-fill-rule": fillRule,
                    "ch03-span-mappers": spanMappers,
                    "ch04-texel-rule": texelRule };

  async function start() {
    const all = document.querySelectorAll("figure[data-live]");
    if (all.length === 0) return;
    window.exactpixelsLiveStartMs = performance.now();
    const m = await loadModule();
    for (const figure of all) {
      const draw = figures[figure.dataset.figure];
      if (!draw) throw new Error("live figures: no figure named " + figure.dataset.figure);
      draw(figure, m);
      figure.hidden = false;
      figure.dataset.live = "ready";
    }
    window.exactpixelsLiveReadyMs = performance.now();
  }

  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", () => start().catch((e) => console.error(e)));
  } else {
    start().catch((e) => console.error(e));
  }
})();
