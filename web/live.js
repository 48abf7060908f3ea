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
  // start-up code) are never called by the figures' functions, except the clock, which
  // chapter 7's renderer reads to time its stages (render_report.hpp): it is given
  // performance.now(); and the environment, which the renderer reads once for
  // EXACTPIXELS_SIMD (fast/simd.hpp): it is given an empty one, so the module takes its
  // only variant, portable. Every other call fails loudly.
  function wasiStubs(memory) {
    const names = ["fd_close", "fd_seek", "fd_write", "proc_exit"];
    const stubs = {};
    for (const name of names) {
      stubs[name] = () => { throw new Error("live figures: unexpected WASI call " + name); };
    }
    stubs.clock_time_get = (id, precision, out) => {
      new DataView(memory().buffer).setBigUint64(
        out, BigInt(Math.round(performance.now() * 1e6)), true);
      return 0; // success
    };
    stubs.environ_sizes_get = (count, bytes) => {
      const view = new DataView(memory().buffer);
      view.setUint32(count, 0, true); // no variables
      view.setUint32(bytes, 0, true); // of no bytes
      return 0;
    };
    stubs.environ_get = () => 0; // nothing to write
    return new Proxy(stubs, {
      get: (target, name) => target[name] ||
        (() => { throw new Error("live figures: unexpected WASI call " + String(name)); }),
    });
  }

  async function loadModule() {
    const bytes = decode(window.exactpixelsModule);
    let memory = null;
    const { instance } = await WebAssembly.instantiate(bytes,
      { wasi_snapshot_preview1: wasiStubs(() => memory) });
    memory = instance.exports.memory;
    instance.exports._initialize();
    const e = { ...instance.exports };
    // The cells array, read through a fresh view after every call (memory may grow).
    e.cells = (count) => new Int32Array(e.memory.buffer, e.ep_cells(), count);
    e.values = (count) => new Float64Array(e.memory.buffer, e.ep_values(), count);
    e.text = () => {
      const bytes = new Uint8Array(e.memory.buffer, e.ep_text(), 256);
      return new TextDecoder().decode(bytes.subarray(0, bytes.indexOf(0)));
    };
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

  // Handles for a triangle's vertices in a W x H grid: steps of 1/8 px, Shift for 1 px;
  // `scale` times CELL screen units per pixel.
  function vertexHandles(svg, v, W, H, update, scale = 1) {
    const bounds = { x0: 0, y0: 0, x1: W, y1: H, bigStep: 1 };
    v.forEach((p, i) => handle(svg, `vertex v${i}`, p, 1 / 8, bounds, update, scale));
  }

  // An image of W x H pixels in an SVG <image>, painted through a canvas: colour(i)
  // gives pixel i's [r, g, b] (0 to 255). Drawn `unit` SVG units per pixel, unsmoothed.
  function pixelImage(parent, W, H, unit) {
    const canvas = document.createElement("canvas");
    canvas.width = W;
    canvas.height = H;
    const node = el("image", { width: W * unit, height: H * unit, class: "live-pixels",
                               preserveAspectRatio: "none" }, parent);
    return (colour) => {
      const context = canvas.getContext("2d");
      const data = context.createImageData(W, H);
      for (let i = 0; i < W * H; ++i) {
        const [r, g, b] = colour(i);
        data.data.set([r, g, b, 255], 4 * i);
      }
      context.putImageData(data, 0, 0);
      node.setAttribute("href", canvas.toDataURL());
    };
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

  // Chapter 2: 8 x 8 blocks rejected, accepted and tested for a triangle.
  function blockWalk(figure, m) {
    const W = 32, H = 24, B = 8, S = 0.5; // S: CELL units per pixel (20 SVG units)
    const u = S * CELL;
    const v = [{ x: 3.5, y: 2.25 }, { x: 29.25, y: 7.5 }, { x: 9.75, y: 21.5 }];
    const svg = newSvg(figure, W * S, H * S, 0.4);
    const blockLayer = el("g", {}, svg);
    const cellLayer = el("g", {}, svg);
    const lines = el("g", { class: "live-grid" }, svg);
    for (let x = 0; x <= W; ++x) el("line", { x1: x * u, y1: 0, x2: x * u, y2: H * u }, lines);
    for (let y = 0; y <= H; ++y) el("line", { x1: 0, y1: y * u, x2: W * u, y2: y * u }, lines);
    const blockLines = el("g", { class: "live-block-grid" }, svg);
    for (let x = 0; x <= W; x += B) el("line", { x1: x * u, y1: 0, x2: x * u, y2: H * u }, blockLines);
    for (let y = 0; y <= H; y += B) el("line", { x1: 0, y1: y * u, x2: W * u, y2: y * u }, blockLines);
    const outline = el("polygon", { class: "live-triangle" }, svg);
    const names = ["", "rejected", "accepted", "tested", "walked directly"];
    function update() {
      const covered = m.ep_blocks(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y, W, H);
      if (covered < 0) return false;
      const cells = m.cells(W * H + (W / B) * (H / B));
      blockLayer.replaceChildren();
      cellLayer.replaceChildren();
      const pixels = [], blocks = [], count = [0, 0, 0, 0, 0];
      for (let j = 0; j < H / B; ++j) {
        for (let i = 0; i < W / B; ++i) {
          const c = cells[W * H + j * (W / B) + i];
          blocks.push(c);
          ++count[c];
          if (c) {
            el("rect", { x: i * B * u, y: j * B * u, width: B * u, height: B * u,
                         class: `live-block-${names[c].split(" ")[0]}` }, blockLayer);
          }
        }
      }
      for (let y = 0; y < H; ++y) {
        for (let x = 0; x < W; ++x) {
          if (cells[y * W + x] !== 1) continue;
          pixels.push([x, y]);
          el("circle", { cx: (x + 0.5) * u, cy: (y + 0.5) * u, r: 3.5, class: "live-tie-won" },
             cellLayer);
        }
      }
      outline.setAttribute("points", v.map((p) => `${p.x * u},${p.y * u}`).join(" "));
      const verdicts = count[4] ? `its bounding box lies within one block, walked pixel by pixel`
        : `of the blocks its bounding box meets, ${count[1]} rejected, ${count[2]} accepted ` +
          `(filled without a test) and ${count[3]} tested pixel by pixel`;
      show(figure, { vertices: v.map((p) => [p.x, p.y]), covered, pixels, blocks },
           `v0 ${point(v[0])}, v1 ${point(v[1])}, v2 ${point(v[2])}: ${verdicts}; ` +
           `${covered} pixels covered.`);
      return true;
    }
    vertexHandles(svg, v, W, H, update, S);
    update();
  }

  // Chapter 8: a floor tilted by the reader, each pixel coloured by its level of detail.
  function floorLevel(figure, m) {
    const W = 48, H = 32, P = 10; // P: SVG units per image pixel
    const tilt = { x: 60, y: 0 }, distance = { x: 6, y: 0 };
    const svg = newSvg(figure, (W * P) / CELL, (H * P + 100) / CELL, 0.4);
    const paint = pixelImage(svg, W, H, P);
    el("rect", { x: 0, y: 0, width: W * P, height: H * P, class: "live-outline" }, svg);
    // Level bands: magnified (level < 0), then [0, 1), [1, 2), ... [5, infinity).
    const bands = [[236, 240, 244], [44, 123, 182], [171, 217, 233], [255, 255, 191],
                   [253, 174, 97], [215, 25, 28], [123, 50, 148]];
    const bandNames = ["< 0", "0", "1", "2", "3", "4", "5+"];
    const band = (level) => level < 0 ? 0 : Math.min(6, 1 + Math.floor(level));
    const legend = el("g", { transform: `translate(0,${H * P + 14})` }, svg);
    bands.forEach((c, i) => {
      el("rect", { x: 44 * i, y: 0, width: 16, height: 12, fill: `rgb(${c.join(",")})`,
                   class: "live-swatch" }, legend);
      el("text", { x: 44 * i + 19, y: 11, class: "live-label" }, legend).textContent = bandNames[i];
    });
    el("text", { x: 44 * 7 + 4, y: 11, class: "live-label" }, legend).textContent = "level";
    const sliders = el("g", { transform: `translate(0,${H * P + 50})` }, svg);
    const tiltLine = el("g", { transform: "translate(10,0)" }, sliders);
    el("line", { x1: 0, y1: 0, x2: 80 * 2.5, y2: 0, class: "live-axis" }, tiltLine);
    const tiltLabel = el("text", { x: 80 * 2.5 + 12, y: 5, class: "live-label" }, tiltLine);
    const distanceLine = el("g", { transform: "translate(10,36)" }, sliders);
    el("line", { x1: 4 * 25, y1: 0, x2: 12 * 25, y2: 0, class: "live-axis" }, distanceLine);
    const distanceLabel = el("text", { x: 12 * 25 + 12, y: 5, class: "live-label" }, distanceLine);
    const n = (x) => Number(x.toPrecision(6));
    function update() {
      const covered = m.ep_level(tilt.x, distance.x);
      if (covered < 0) return false;
      const cells = m.cells(W * H);
      const values = m.values(W * H + 2);
      const levels = [], count = [0, 0, 0, 0, 0, 0, 0];
      for (let i = 0; i < W * H; ++i) {
        levels.push(cells[i] === 1 ? values[i] : null);
        if (cells[i] === 1) ++count[band(values[i])];
      }
      paint((i) => levels[i] === null ? [255, 255, 255] : bands[band(levels[i])]);
      tiltLabel.textContent = `tilt ${tilt.x}°`;
      distanceLabel.textContent = `distance ${distance.x}`;
      const centre = values[W * H], closed = values[W * H + 1];
      const shares = count.map((c, i) => c ? `${c} at level ${bandNames[i]}` : "")
        .filter((t) => t).join(", ");
      show(figure, { tilt: tilt.x, distance: distance.x, covered, levels, centre, closedForm: closed },
           `Tilt ${tilt.x}°, distance ${distance.x}: ${covered} pixels of floor, ${shares}. ` +
           `At the image centre the level is ${n(centre)}; the closed form ` +
           `log2(s d / (f cos a)) gives ${n(closed)}.`);
      return true;
    }
    handle(tiltLine, "floor tilt in degrees", tilt, 5, { x0: 0, y0: 0, x1: 80, y1: 0, bigStep: 15 },
           update, 2.5 / CELL);
    handle(distanceLine, "floor distance", distance, 0.5, { x0: 4, y0: 0, x1: 12, y1: 0, bigStep: 2 },
           update, 25 / CELL);
    update();
  }

  // Chapter 7: the camera moved about a small scene (web/live_scene.hpp), drawn by
  // render_scene, with what the geometry and depth stages decided.
  function sceneCamera(figure, m) {
    const W = 64, H = 40, P = 6;   // the image, SVG units per pixel
    const R = 7, S = 16;           // the plan reaches +-R world units, S SVG units each
    const cam = { x: 4, y: 5 };    // the camera on the plan: world x and -z (down = -z)
    const planX = W * P + 24 + R * S, planY = R * S;
    const svg = newSvg(figure, (W * P + 24 + 2 * R * S) / CELL,
                       Math.max(H * P + 40, 2 * R * S) / CELL, 0.4);
    const paint = pixelImage(svg, W, H, P);
    el("rect", { x: 0, y: 0, width: W * P, height: H * P, class: "live-outline" }, svg);
    const plan = el("g", { transform: `translate(${planX},${planY})` }, svg);
    el("rect", { x: -R * S, y: -R * S, width: 2 * R * S, height: 2 * R * S,
                 class: "live-outline" }, plan);
    const tris = el("g", {}, plan);
    const clip = el("clipPath", { id: "live-plan-clip" }, plan);
    el("rect", { x: -R * S, y: -R * S, width: 2 * R * S, height: 2 * R * S }, clip);
    const wedge = el("g", { "clip-path": "url(#live-plan-clip)" }, plan);
    const kinds = ["drawn", "rejected", "clipped", "culled"];
    const legend = el("g", { transform: `translate(0,${H * P + 22})` }, svg);
    kinds.forEach((k, i) => {
      el("rect", { x: 92 * i, y: 0, width: 16, height: 12, class: `live-tri-${k}` }, legend);
      el("text", { x: 92 * i + 20, y: 11, class: "live-label" }, legend).textContent = k;
    });
    const hfov = Math.atan(Math.tan(Math.PI / 6) * W / H); // half the horizontal angle
    function update() {
      const count = m.ep_scene(cam.x, -cam.y);
      if (count < 0) return false;
      const cells = m.cells(2576 + 4 * count);
      const corners = m.values(6 * count);
      const image = Array.from(cells.subarray(0, W * H));
      paint((i) => [image[i] >> 16 & 255, image[i] >> 8 & 255, image[i] & 255]);
      const r = Array.from(cells.subarray(2560, 2570));
      const reason = m.text();
      const flags = [], culledPieces = [], pieces = [], pixels = [];
      tris.replaceChildren();
      for (let k = 0; k < count; ++k) {
        const t = cells.subarray(2576 + 4 * k, 2580 + 4 * k);
        flags.push(t[0]);
        culledPieces.push(t[1]);
        pieces.push(t[2]);
        pixels.push(t[3]);
        const kind = t[0] & 1 ? "rejected" : t[2] === 0 && t[1] > 0 ? "culled"
          : t[0] & 2 ? "clipped" : "drawn";
        const points = [0, 1, 2].map((c) =>
          `${corners[6 * k + 2 * c] * S},${-corners[6 * k + 2 * c + 1] * S}`).join(" ");
        el("polygon", { points, class: `live-tri-${kind}` }, tris);
      }
      // The horizontal field of view, drawn from the camera towards the target (the
      // plan's origin; atan2 of the plan's y, which points down, that is towards -z).
      wedge.replaceChildren();
      for (const side of [-1, 1]) {
        const a = Math.atan2(-cam.y, -cam.x) + side * hfov;
        el("line", { x1: cam.x * S, y1: cam.y * S, x2: (cam.x + 30 * Math.cos(a)) * S,
                     y2: (cam.y + 30 * Math.sin(a)) * S, class: "live-axis" }, wedge);
      }
      const [geometry, rejected, clipped, culled, drawn, covered, depthOn, tested, hidden] = r;
      show(figure, { camera: [cam.x, -cam.y], triangles: count, geometry, rejected, clipped,
                     culled, drawn, covered, depthOn: depthOn === 1, tested, hidden, reason,
                     flags, culledPieces, pieces, pixels, image },
           `Camera at (${cam.x}, 1.5, ${-cam.y}), looking at (0, 0.8, 0): of ${count} ` +
           `triangles, ${rejected} rejected (wholly outside one plane of the view volume), ` +
           `${clipped} clipped (cut at the near plane, the far plane at depth 12 or the ` +
           `guard band), ${culled} culled (back faces); ${drawn} drawn, covering ` +
           `${covered} pixels. Depth stage ${depthOn ? "on" : "off"} (${reason})` +
           (depthOn ? `: ${tested} pixels tested, ${hidden} hidden.` : "."));
      return true;
    }
    handle(plan, "camera", cam, 1 / 4, { x0: -R, y0: -R, x1: R, y1: R, bigStep: 1 }, update,
           S / CELL);
    update();
  }

  const figures = { "ch00-edge-centres": edgeCentres, "ch01-scanline": scanline, "ch02-fill-rule": fillRule,
                    "ch03-span-mappers": spanMappers,
                    "ch04-texel-rule": texelRule, "ch02-blocks": blockWalk,
                    "ch07-scene": sceneCamera, "ch08-level": floorLevel };

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
