// renderPlot(container, plot): a small SVG line plot (linear or log axes) for solution panels and the graphs panel. No dependencies.
// plot: {title, x_label, y_label, log_x, log_y, series: [{name, x, y, dots?}], description?, bands?, markers?};
// non-finite points are skipped. A series with dots draws points, not a line; bands ([{from, to, label}], on x) are
// shaded behind the data, markers ([{x, label}]) are labelled vertical lines, and y = 0 is drawn when in range.
import { formatNumber } from "./format.js";

export const renderPlot = (function () {
  const COLORS = ["#1f5eea", "#d1495b", "#2e8b57", "#8e44ad", "#e08e0b", "#555"];
  const NS = "http://www.w3.org/2000/svg";
  const W = 640, H = 360, M = { l: 74, r: 16, t: 30, b: 50 };
  let described = 0;

  function el(name, attrs, text) {
    const node = document.createElementNS(NS, name);
    for (const [k, v] of Object.entries(attrs || {})) node.setAttribute(k, v);
    if (text !== undefined) node.textContent = text;
    return node;
  }

  function niceTicks(lo, hi, count) {
    const span = hi - lo || Math.abs(hi) || 1;
    const step0 = span / count;
    const mag = Math.pow(10, Math.floor(Math.log10(step0)));
    const step = [1, 2, 5, 10].map((f) => f * mag).find((s) => span / s <= count) || 10 * mag;
    const ticks = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) ticks.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    return ticks;
  }

  // A tick's label: short, an exponent alone beyond 10^4 or under 10^-2.
  const fmt = (v) => formatNumber(v, { digits: 4, expDigits: 0, large: 1e4, small: 1e-2 });

  function axis(values, log) {
    const finite = values.filter((v) => Number.isFinite(v) && (!log || v > 0));
    let lo = Math.min(...finite), hi = Math.max(...finite);
    if (log) { lo = Math.floor(Math.log10(lo)); hi = Math.ceil(Math.log10(hi)); if (lo === hi) hi = lo + 1; }
    else if (lo === hi) { lo -= 1; hi += 1; }
    else { const pad = 0.04 * (hi - lo); lo -= pad; hi += pad; }
    const ticks = log ? Array.from({ length: hi - lo + 1 }, (_, i) => lo + i) : niceTicks(lo, hi, 6);
    const step = log ? Math.max(1, Math.ceil(ticks.length / 8)) : 1;
    return { lo, hi, ticks: ticks.filter((_, i) => i % step === 0), log };
  }

  function render(container, plot) {
    container.innerHTML = "";
    container.classList.add("plot");
    const xs = plot.series.flatMap((s) => s.x), ys = plot.series.flatMap((s) => s.y);
    const ax = axis(xs, plot.log_x), ay = axis(ys, plot.log_y);
    const tx = (v) => M.l + ((plot.log_x ? Math.log10(v) : v) - ax.lo) / (ax.hi - ax.lo) * (W - M.l - M.r);
    const ty = (v) => H - M.b - ((plot.log_y ? Math.log10(v) : v) - ay.lo) / (ay.hi - ay.lo) * (H - M.t - M.b);
    const svg = el("svg", { viewBox: `0 0 ${W} ${H}`, role: "img", "aria-label": plot.title });
    if (plot.description) {
      // A screen reader's summary of what is plotted (e.g. the graphs panel's ranges and point count).
      const id = `plot-desc-${++described}`;
      svg.appendChild(el("title", {}, plot.title));
      svg.appendChild(el("desc", { id }, plot.description));
      svg.setAttribute("aria-describedby", id);
    }
    svg.appendChild(el("text", { x: W / 2, y: 18, "text-anchor": "middle", "font-size": 15, "font-weight": 600 }, plot.title));
    for (const t of ax.ticks) {
      const x = M.l + (t - ax.lo) / (ax.hi - ax.lo) * (W - M.l - M.r);
      svg.appendChild(el("line", { x1: x, x2: x, y1: M.t, y2: H - M.b, stroke: "#e3e6ec" }));
      svg.appendChild(el("text", { x, y: H - M.b + 16, "text-anchor": "middle", "font-size": 12 }, ax.log ? `1e${t}` : fmt(t)));
    }
    for (const t of ay.ticks) {
      const y = H - M.b - (t - ay.lo) / (ay.hi - ay.lo) * (H - M.t - M.b);
      svg.appendChild(el("line", { x1: M.l, x2: W - M.r, y1: y, y2: y, stroke: "#e3e6ec" }));
      svg.appendChild(el("text", { x: M.l - 6, y: y + 4, "text-anchor": "end", "font-size": 12 }, ay.log ? `1e${t}` : fmt(t)));
    }
    for (const band of plot.bands || []) {
      const x1 = tx(Math.max(band.from, ax.lo)), x2 = tx(Math.min(band.to, ax.hi));
      svg.appendChild(el("rect", { x: x1, y: M.t, width: Math.max(0, x2 - x1), height: H - M.t - M.b, fill: "#d8f0dc", class: "band" }));
      if (band.label) svg.appendChild(el("text", { x: (x1 + x2) / 2, y: M.t + 14, "text-anchor": "middle", "font-size": 12, fill: "#1d6b33" }, band.label));
    }
    if ((plot.bands || plot.markers) && ay.lo < 0 && ay.hi > 0 && !plot.log_y) {
      svg.appendChild(el("line", { x1: M.l, x2: W - M.r, y1: ty(0), y2: ty(0), stroke: "#6b7280" }));
    }
    (plot.markers || []).forEach((marker, i) => {
      const x = tx(marker.x);
      svg.appendChild(el("line", { x1: x, x2: x, y1: M.t, y2: H - M.b, stroke: "#374151", "stroke-dasharray": "4 3", class: "marker" }));
      svg.appendChild(el("text", { x: x + 4, y: M.t + 30 + 14 * i, "font-size": 12, fill: "#111827" }, marker.label));
    });
    svg.appendChild(el("rect", { x: M.l, y: M.t, width: W - M.l - M.r, height: H - M.t - M.b, fill: "none", stroke: "#9aa3b2" }));
    svg.appendChild(el("text", { x: (M.l + W - M.r) / 2, y: H - 10, "text-anchor": "middle", "font-size": 13 }, plot.x_label));
    svg.appendChild(el("text", { x: 16, y: (M.t + H - M.b) / 2, "text-anchor": "middle", "font-size": 13, transform: `rotate(-90 16 ${(M.t + H - M.b) / 2})` }, plot.y_label));
    const legend = document.createElement("div");
    legend.className = "legend";
    plot.series.forEach((s, i) => {
      const color = COLORS[i % COLORS.length];
      const pts = [];
      s.x.forEach((x, j) => {
        const y = s.y[j];
        if (Number.isFinite(x) && Number.isFinite(y) && (!plot.log_x || x > 0) && (!plot.log_y || y > 0)) pts.push(`${tx(x).toFixed(1)},${ty(y).toFixed(1)}`);
      });
      if (s.dots) {
        const dots = el("g", { fill: color });
        for (const pt of pts) {
          const [cx, cy] = pt.split(",");
          dots.appendChild(el("circle", { cx, cy, r: 1.8 }));
        }
        svg.appendChild(dots);
      } else {
        svg.appendChild(el("polyline", { points: pts.join(" "), fill: "none", stroke: color, "stroke-width": i === 0 ? 2.5 : 1.6, "stroke-dasharray": i === 0 ? "" : "6 4" }));
      }
      const item = document.createElement("span");
      item.style.setProperty("--c", color);
      item.textContent = s.name;
      legend.appendChild(item);
    });
    container.appendChild(svg);
    container.appendChild(legend);
  }

  return render;
})();
