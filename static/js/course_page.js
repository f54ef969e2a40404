// The course page: the shared page behaviour, and this learner's practice per section (practice_list.js).
import "./common.js";
import { showCourseProgress } from "./practice_list.js";

showCourseProgress();
