//! Physics-aware pose optimization: refines each object's 5-DoF pose (uniform scale, yaw about
//! +Y, translation) in scene-graph breadth-first order against pose-alignment, SDF collision and
//! stability losses, behind an `Optimizer` seam so that solvers can be swapped.
