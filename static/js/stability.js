// Lesson page: the eigenvalues of a system built of parts, linearised about its reference motion, plotted against one
// parameter (a bicycle's speed). Asks POST /api/systems/{id}/eigenvalues with a sweep; shades where every real part is
// negative (stable), marks where stability changes (the weave and capsize speeds), and asks again when the scene's
// design parameters change (seen on its live numbers).
import { apiPatient } from "./api.js";
import { config } from "./config.js";
import { element as el } from "./dom.js";
import { formatNumber } from "./format.js";
import { lesson } from "./lesson.js";
import { renderPlot } from "./plot.js";

(function () {
  const systems = config.linearised || [];
  const section = document.getElementById("linearised");
  if (!systems.length || !section) return;
  section.hidden = false;
  const POINTS = 101;
  // Asked once the page's scene has started, as the derivations are (its viewer's start comes first).
  const SCENE_FIRST_MS = 4000;
  const sceneFirst = !config.scene ? Promise.resolve() : new Promise((resolve) => {
    document.addEventListener("dynlab:live", resolve, { once: true });
    setTimeout(resolve, SCENE_FIRST_MS);
  });
  const number = (v) => formatNumber(v, { digits: 4 });

  function nameOf(system, crossing) {
    const named = system.crossing_names.find((c) => c.becomes === crossing.becomes && c.oscillating === crossing.oscillating);
    return named ? named.name : `${crossing.becomes} from`;
  }

  // Where every real part is negative, from the crossings and the first value's answer.
  function stableBands(sweep) {
    const edges = [sweep.values[0], ...sweep.crossings.map((c) => c.value), sweep.values[sweep.values.length - 1]];
    let stable = Math.max(...sweep.eigenvalues[0].map((e) => e.re)) < 0;
    const bands = [];
    for (let i = 0; i + 1 < edges.length; i++) {
      if (stable) bands.push({ from: edges[i], to: edges[i + 1], label: "stable" });
      stable = !stable;
    }
    return bands;
  }

  for (const system of systems) {
    const heading = el("h2", {}, `${system.title}: eigenvalues against ${system.label}`);
    const about = el("p", { class: "about" }, `Linearised about ${system.about}; dots: real parts (growth rate, 1/s) and imaginary parts (frequency, rad/s) of every eigenvalue.`);
    const plot = el("div", { class: "stability-plot" });
    // Where the frequencies dwarf the growth rates (a rattleback: 100 rad/s against 2 1/s), they get a plot of their own.
    const frequencies = el("div", { class: "stability-plot stability-frequencies", hidden: "" });
    const summary = el("p", { class: "stability-summary", role: "status" }, "computing…");
    const box = el("article", { class: "stability", "data-system": system.id }, heading, about, plot, frequencies, summary);
    section.appendChild(box);
    let asked = null;

    async function draw() {
      const values = (lesson && lesson.session && lesson.session.values) || {};
      const params = {};
      for (const name of system.parameters) if (name !== system.parameter && name in values) params[name] = values[name];
      const key = JSON.stringify(params);
      if (key === asked) return;
      asked = key;
      summary.textContent = "computing…";
      try {
        const answer = await apiPatient("POST", `/api/systems/${encodeURIComponent(system.id)}/eigenvalues`, {
          params, sweep: { parameter: system.parameter, low: system.low, high: system.high, points: POINTS },
        });
        if (asked !== key) return; // the design changed meanwhile: the newer answer draws
        const sweep = answer.sweep;
        const re = { name: "Re λ (1/s)", x: [], y: [], dots: true }, im = { name: "Im λ (rad/s)", x: [], y: [], dots: true };
        sweep.values.forEach((v, i) => sweep.eigenvalues[i].forEach((e) => {
          re.x.push(v); re.y.push(e.re);
          if (e.im > 0) { im.x.push(v); im.y.push(e.im); }
        }));
        const markers = sweep.crossings.map((c) => ({ x: c.value, label: `${nameOf(system, c)} ${number(c.value)} ${sweep.unit}` }));
        const bands = stableBands(sweep);
        const said = sweep.crossings.map((c) => `${nameOf(system, c)} ${number(c.value)} ${sweep.unit}`).join(", ");
        const description = `${POINTS} values of ${system.parameter} from ${system.low} to ${system.high} ${sweep.unit}; ${said || "no change of stability"}.`;
        const largest = (ys) => ys.reduce((m, y) => Math.max(m, Math.abs(y)), 0);
        const apart = largest(im.y) > 5 * Math.max(largest(re.y), 1e-12);
        if (apart) {
          renderPlot(plot, {
            title: `Growth rates against ${system.label}`,
            x_label: system.label, y_label: "Re λ (1/s)", series: [re], bands, markers, description,
          });
          frequencies.hidden = false;
          renderPlot(frequencies, {
            title: `Frequencies against ${system.label}`,
            x_label: system.label, y_label: "Im λ (rad/s)", series: [im], bands: [], markers: [], description,
          });
        } else {
          frequencies.hidden = true;
          renderPlot(plot, {
            title: `Eigenvalues against ${system.label}`,
            x_label: system.label, y_label: "eigenvalue", series: [re, im], bands, markers, description,
          });
        }
        summary.textContent = bands.length
          ? `Stable (every real part negative) for ${bands.map((b) => `${number(b.from)}–${number(b.to)} ${sweep.unit}`).join(" and ")}: ${said}.`
          : `Unstable at every ${system.parameter} from ${system.low} to ${system.high} ${sweep.unit}.`;
        box.dataset.crossings = JSON.stringify(sweep.crossings.map((c) => c.value));
      } catch (err) {
        summary.textContent = `The eigenvalues could not be computed: ${err.message}`;
        asked = null;
      }
    }

    sceneFirst.then(draw);
    document.addEventListener("dynlab:live", () => { sceneFirst.then(draw); });
  }
})();
