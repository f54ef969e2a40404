// The Solver lab page: its text's equations.
import "./common.js";
import { renderMath } from "./katex.js";

renderMath();
