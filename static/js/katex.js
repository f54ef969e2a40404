// Equations with KaTeX (vendored in static/vendor/katex, a classic script that defines its own global `katex`; no
// CDN, so a classroom can be offline). Imported here only: every page script draws equations through this module.
import "../vendor/katex/katex.min.js";

const katex = globalThis.katex;

// `latex` drawn into `el` (display: a block equation); the source text if KaTeX is missing.
export function katexInto(el, latex, display) {
  if (katex) katex.render(latex, el, { displayMode: display, throwOnError: false });
  else el.textContent = latex;
}

// Every `.math` element under `root` (the lesson text's $…$ and $$…$$), drawn from its text: those above one and a
// half window heights now, the rest top down, MATH_CHUNK_MS at a time, whenever the page's thread is idle (and at
// least every MATH_LATER_MS). Typesetting a whole lesson (50–200 equations) and laying it out takes a good part of the
// thread that the lesson's viewer, in the same page, needs for its start; what is below the window can wait for it.
const MATH_LATER_MS = 300;
const MATH_CHUNK_MS = 8;
export function renderMath(root = document) {
  const draw = (el) => katexInto(el, el.textContent, el.classList.contains("math-display"));
  const all = [...root.querySelectorAll(".math")];
  const near = all.map((el) => el.getBoundingClientRect().top < 1.5 * window.innerHeight); // one layout, then drawing
  const later = all.filter((el, i) => !near[i]);
  all.forEach((el, i) => { if (near[i]) draw(el); });
  const whenIdle = window.requestIdleCallback || ((fn) => setTimeout(() => fn({ timeRemaining: () => 0 }), 16));
  const drawSome = (deadline) => {
    const until = performance.now() + Math.max(deadline.timeRemaining(), MATH_CHUNK_MS);
    do draw(later.shift()); while (later.length && performance.now() < until);
    if (later.length) whenIdle(drawSome, { timeout: MATH_LATER_MS });
  };
  if (later.length) whenIdle(drawSome, { timeout: MATH_LATER_MS });
}
