//! Planning agents: turn a prompt into a scene plan (objects, anchor, hierarchy, relations) and
//! a plan into an initial layout, behind `Planner` and `Guide` seams with offline defaults and
//! online model providers.
