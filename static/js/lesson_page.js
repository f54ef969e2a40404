// The lesson page: the lesson text's equations, then its parts (each imports what it uses; lesson.js, which they
// share, runs first).
import "./common.js";
import { renderMath } from "./katex.js";
import "./lesson.js";
import "./room.js";
import "./time_controls.js";
import "./viewer_toolbar.js";
import "./graphs.js";
import "./derivations.js";

renderMath();
