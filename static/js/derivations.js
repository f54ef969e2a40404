// Lesson page: the equations of motion of a catalogue system by every formulation, side by side.
// Each column asks POST /api/systems/{id}/derive (cached on the server after the first time) and
// renders the equations and the steps with KaTeX; a formulation that does not apply says why.
import { api } from "./api.js";
import { config } from "./config.js";
import { katexInto } from "./katex.js";

(function () {
  const systems = config.derivations || [];
  const section = document.getElementById("derivations");
  if (!systems.length || !section) return;
  section.hidden = false;

  const seconds = (s) => (s < 0.01 ? `${(1000 * s).toFixed(1)} ms` : `${s.toFixed(2)} s`);

  // Derived once the page's scene has started (its first live numbers, or after SCENE_FIRST_MS): the columns sit
  // below the scene, and their answers' equations would otherwise compete with the viewer's start for the page's thread.
  const SCENE_FIRST_MS = 4000;
  const sceneFirst = !config.scene ? Promise.resolve() : new Promise((resolve) => {
    document.addEventListener("dynlab:live", resolve, { once: true });
    setTimeout(resolve, SCENE_FIRST_MS);
  });
  const derive = (systemId, formulation) => api("POST", `/api/systems/${encodeURIComponent(systemId)}/derive`, { formulation });

  function column(system, formulation) {
    const col = document.createElement("article");
    col.className = "formulation";
    col.dataset.formulation = formulation.id;
    const h = document.createElement("h3");
    h.textContent = formulation.title;
    col.appendChild(h);
    if (formulation.unavailable) {
      col.classList.add("unavailable");
      const p = document.createElement("p");
      p.className = "why";
      p.textContent = `Does not apply here: ${formulation.unavailable}.`;
      col.appendChild(p);
      return col;
    }
    const status = document.createElement("p");
    status.className = "status";
    status.textContent = "deriving…";
    col.appendChild(status);
    sceneFirst.then(() => derive(system.id, formulation.id)).then((answer) => {
      status.textContent = `in ${answer.variables} · ${answer.cached ? "from the cache" : `derived in ${seconds(answer.derive_s)}`}, code ${seconds(answer.compile_s)}`;
      const equations = document.createElement("div");
      equations.className = "equations";
      for (const latex of answer.equations_latex) {
        const eq = document.createElement("div");
        katexInto(eq, latex, true);
        equations.appendChild(eq);
      }
      col.appendChild(equations);
      const details = document.createElement("details");
      const summary = document.createElement("summary");
      summary.textContent = `Steps (${answer.steps.length})`;
      details.appendChild(summary);
      for (const step of answer.steps) {
        const div = document.createElement("div");
        div.className = "step";
        const title = document.createElement("h4");
        title.textContent = step.title;
        const eq = document.createElement("div");
        katexInto(eq, step.latex, true);
        div.append(title, eq);
        details.appendChild(div);
      }
      col.appendChild(details);
      col.dataset.ready = "true";
    }).catch((error) => {
      status.className = "status error";
      status.textContent = `Could not derive: ${error.details ? error.details.map((d) => d.msg).join("; ") : error.message}`;
    });
    return col;
  }

  const heading = document.createElement("h2");
  heading.textContent = "The same motion, formulation by formulation";
  section.appendChild(heading);
  const note = document.createElement("p");
  note.className = "note";
  note.textContent = "Each column is derived by the server from one description of the system. The scene's readout shows how far apart their accelerations are on the running state.";
  section.appendChild(note);
  for (const system of systems) {
    const wrap = document.createElement("div");
    wrap.className = "derivation";
    wrap.dataset.system = system.id;
    const title = document.createElement("h3");
    title.className = "system-title";
    title.textContent = system.title;
    const assumptions = document.createElement("p");
    assumptions.className = "note";
    assumptions.textContent = system.assumptions;
    const grid = document.createElement("div");
    grid.className = "formulation-grid";
    grid.tabIndex = 0;
    grid.setAttribute("role", "region");
    grid.setAttribute("aria-label", `${system.title}: equations by formulation`);
    for (const formulation of system.formulations) grid.appendChild(column(system, formulation));
    wrap.append(title, assumptions, grid);
    section.appendChild(wrap);
  }
})();
