// Equations with KaTeX (vendored in static/vendor/katex, a classic script that defines its own global `katex`; no
// CDN, so a classroom can be offline). Imported here only: every page script draws equations through this module.
import "../vendor/katex/katex.min.js";

const katex = globalThis.katex;

// `latex` drawn into `el` (display: a block equation); the source text if KaTeX is missing.
export function katexInto(el, latex, display) {
  if (katex) katex.render(latex, el, { displayMode: display, throwOnError: false });
  else el.textContent = latex;
}

// Every `.math` element under `root` (the lesson text's $…$ and $$…$$), drawn from its text.
export function renderMath(root = document) {
  root.querySelectorAll(".math").forEach((el) => katexInto(el, el.textContent, el.classList.contains("math-display")));
}
