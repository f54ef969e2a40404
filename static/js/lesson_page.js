// The lesson page: the lesson text's equations, then its parts (each imports what it uses; lesson.js, which they
// share, runs first), and after the text its section's exercises.
import "./common.js";
import { config } from "./config.js";
import { renderMath } from "./katex.js";
import { listSectionExercises } from "./practice_list.js";
import "./lesson.js";
import "./room.js";
import "./time_controls.js";
import "./viewer_toolbar.js";
import "./graphs.js";
import "./derivations.js";
import "./stability.js";

renderMath();

const prevnext = document.querySelector("article.lesson-text nav.prevnext");
if (config.section && prevnext) listSectionExercises(config.section, prevnext);
