// Keyboard access to the boxes that scroll sideways (a wide equation in the text, a step of a worked
// solution, a derived equation, a wide table): while a box does overflow it is a tab stop with a name, so a keyboard
// user can reach it and scroll it with the arrow keys; when it fits again (a wider window) it is not.
(function () {
  const SCROLL_BOXES = ".math-display, .solution .step > div, .formulation .equations > div, .formulation .step > div, .table-wrap";
  const LABEL = "Equation (scroll sideways with the arrow keys)";
  const TABLE_LABEL = "Table (scroll sideways with the arrow keys)";

  function markScrollBoxes() {
    for (const box of document.querySelectorAll(SCROLL_BOXES)) {
      const overflows = box.scrollWidth > box.clientWidth + 1;
      if (overflows && !box.hasAttribute("data-keyboard-scroll")) {
        box.dataset.keyboardScroll = "";
        box.tabIndex = 0;
        box.setAttribute("role", "group");
        box.setAttribute("aria-label", box.matches(".table-wrap") ? TABLE_LABEL : LABEL);
      } else if (!overflows && box.hasAttribute("data-keyboard-scroll")) {
        delete box.dataset.keyboardScroll;
        for (const name of ["tabindex", "role", "aria-label"]) box.removeAttribute(name);
      }
    }
  }

  // At most one pass per animation frame, however many changes arrive (the readout redraws every second).
  let queued = false;
  function schedule() {
    if (queued) return;
    queued = true;
    requestAnimationFrame(() => { queued = false; markScrollBoxes(); });
  }

  // A module runs once the document is parsed: mark the boxes now, and again when anything changes.
  schedule();
  // Content drawn later (worked solutions, derivations, an opened <details>, projector mode's larger text).
  new MutationObserver(schedule).observe(document.body, {
    childList: true, subtree: true, attributes: true, attributeFilter: ["open", "hidden", "class"],
  });
  window.addEventListener("resize", schedule);
  // A web font (KaTeX's) that arrives late widens an equation without any change to the page's elements.
  if (document.fonts) document.fonts.addEventListener("loadingdone", schedule);
})();
