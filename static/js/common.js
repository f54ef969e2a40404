// Shared by every page: projector (large text) mode, remembered per browser, and dynlabElement (below).

// An element: attributes set as given ("text" sets its text; null, undefined or false leave one out; true sets it
// empty), then the children (nodes or strings) appended.
window.dynlabElement = function (tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attrs)) {
    if (name === "text") node.textContent = value;
    else if (value !== null && value !== undefined && value !== false) node.setAttribute(name, value === true ? "" : value);
  }
  node.append(...children);
  return node;
};

(function () {
  const root = document.documentElement;
  const apply = (on) => {
    root.classList.toggle("large", on);
    const button = document.getElementById("large-text");
    if (button) button.setAttribute("aria-pressed", String(on));
  };
  apply(localStorage.getItem("dynlab.large") === "1");
  const toggle = () => {
    const on = !root.classList.contains("large");
    localStorage.setItem("dynlab.large", on ? "1" : "0");
    apply(on);
  };
  document.addEventListener("DOMContentLoaded", () => {
    apply(localStorage.getItem("dynlab.large") === "1");
    const button = document.getElementById("large-text");
    if (button) button.addEventListener("click", toggle);
    document.querySelectorAll(".math").forEach((el) => {
      if (window.katex) {
        katex.render(el.textContent, el, { displayMode: el.classList.contains("math-display"), throwOnError: false });
      }
    });
  });
  document.addEventListener("keydown", (e) => {
    if (e.altKey && (e.key === "l" || e.key === "L")) { e.preventDefault(); toggle(); }
  });
})();
