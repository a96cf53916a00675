//! Walk and Reach: a top-down raster of the floor, eroded by a round robot, with object
//! footprints removed, split into 8-connected walkable components.

use serde::{Deserialize, Serialize};

use scenethesis_scene_graph::{Components, Floor, FloorRaster, Wall, WallBox};

use crate::scene::{EvalObject, EvalScene};

/// Raster resolution in pixels along each side.
pub const RASTER_SIZE: usize = 256;
/// Margin (m) added on every side of the floor's bounding square.
pub const RASTER_MARGIN: f64 = 0.2;
/// Robot radius (m): half of its 0.3 m diameter (the shared constant of `scenethesis-scene-graph`).
pub use scenethesis_scene_graph::ROBOT_RADIUS;
/// For Walk, only objects whose bounding-box centre is below this height (m) are obstacles.
pub const WALK_HEIGHT_LIMIT: f64 = 1.5;

/// The Walk and Reach results of one scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WalkReach {
    /// Largest walkable component / all walkable area (objects below 1.5 m are obstacles);
    /// 0 when nothing is walkable.
    pub walk: f64,
    /// Reach over the floor-standing objects (parent = ground); `None` when there are none.
    pub reach_floor: Option<f64>,
    /// Reach over every object; `None` for a scene without objects.
    pub reach_all: Option<f64>,
    /// Walkable area (m²) of the Walk raster.
    pub walkable_area: f64,
    /// Number of walkable components of the Walk raster.
    pub walk_components: usize,
    /// Floor-standing objects that touch no walkable component of the Reach raster.
    pub unreachable_floor_objects: Vec<String>,
}

/// A rectangle on the floor plane with its own axes, in (x, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorRect {
    /// Centre (x, z).
    pub center: [f64; 2],
    /// Unit direction of the first axis (x, z); the second is its perpendicular.
    pub axis: [f64; 2],
    /// Half extents along the first and second axes.
    pub half: [f64; 2],
}

impl FloorRect {
    /// Euclidean distance from the (x, z) point to the rectangle (0 inside).
    pub fn distance(&self, x: f64, z: f64) -> f64 {
        let (dx, dz) = (x - self.center[0], z - self.center[1]);
        let u = dx * self.axis[0] + dz * self.axis[1];
        let v = -dx * self.axis[1] + dz * self.axis[0];
        let qu = (u.abs() - self.half[0]).max(0.0);
        let qv = (v.abs() - self.half[1]).max(0.0);
        qu.hypot(qv)
    }

    /// The (x, z) box around the rectangle grown by `r`: (min x, min z, max x, max z).
    fn bounds(&self, r: f64) -> [f64; 4] {
        let (a, b) = (self.axis, [-self.axis[1], self.axis[0]]);
        let ex = (a[0] * self.half[0]).abs() + (b[0] * self.half[1]).abs() + r;
        let ez = (a[1] * self.half[0]).abs() + (b[1] * self.half[1]).abs() + r;
        [
            self.center[0] - ex,
            self.center[1] - ez,
            self.center[0] + ex,
            self.center[1] + ez,
        ]
    }
}

/// An object's footprint: the box of its mesh in its own (yawed) frame, projected on the floor.
pub fn footprint(object: &EvalObject) -> Option<FloorRect> {
    let (s, c) = object.yaw.sin_cos();
    // World → object frame: x_l = c·x − s·z, z_l = s·x + c·z.
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in object.mesh.parts.iter().flat_map(|p| p.positions.iter()) {
        let (x, z) = (p[0] as f64, p[2] as f64);
        let l = [c * x - s * z, s * x + c * z];
        for k in 0..2 {
            lo[k] = lo[k].min(l[k]);
            hi[k] = hi[k].max(l[k]);
        }
    }
    if !lo[0].is_finite() {
        return None;
    }
    let (cu, cv) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
    // Object frame → world: x = c·u + s·v, z = −s·u + c·v.
    Some(FloorRect {
        center: [c * cu + s * cv, -s * cu + c * cv],
        axis: [c, -s],
        half: [(hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0],
    })
}

/// A solid box of architecture standing upright: a piece of wall between, below or above its
/// door and window openings, or a window's glass pane.
#[derive(Debug, Clone, PartialEq)]
pub struct WallPiece {
    /// Id of the wall it belongs to, or of the window whose pane it is.
    pub wall: String,
    /// Its rectangle on the floor plane (length along the wall, thickness across).
    pub rect: FloorRect,
    /// Height of its bottom above the floor (m): 0 for a piece standing on the floor.
    pub bottom: f64,
    /// Height of its top above the floor (m).
    pub height: f64,
}

impl WallPiece {
    /// Whether it stands on the floor (and so blocks whoever walks there).
    pub fn on_floor(&self) -> bool {
        self.bottom <= 0.0
    }
}

/// The solid pieces of the walls, cut around their door and window openings as every exporter
/// cuts them ([`scenethesis_scene_graph::Architecture::wall_spans`]: piers, the wall under a window's sill, lintels),
/// then each window's pane ([`scenethesis_scene_graph::Architecture::window_pane`]).
pub fn wall_pieces(scene: &EvalScene) -> Vec<WallPiece> {
    let arch = &scene.architecture;
    let piece = |id: &str, wall: &Wall, span: &WallBox| {
        let d = wall.direction();
        let c = span.center(wall);
        let half = span.half_extents();
        WallPiece {
            wall: id.to_owned(),
            rect: FloorRect {
                center: [c.x, c.z],
                axis: [d.x, d.y],
                half: [half.x, half.z],
            },
            bottom: span.bottom,
            height: span.top,
        }
    };
    let walls = (arch.walls.iter())
        .flat_map(|wall| (arch.wall_spans(wall).into_iter()).map(move |span| (wall, span)))
        .map(|(wall, span)| piece(&wall.id, wall, &span));
    let panes = (arch.windows.iter())
        .filter_map(|w| Some((w, arch.window_pane(w)?)))
        .map(|(window, (wall, pane))| piece(&window.id, wall, &pane));
    walls.chain(panes).collect()
}

/// The raster the Walk and Reach metrics use for `floor`: `RASTER_SIZE` × `RASTER_SIZE` cells
/// over the floor's bounding square plus `RASTER_MARGIN` on every side.
pub fn metric_grid(floor: &Floor) -> FloorRaster {
    let ext = floor.extent();
    let side = ext.x.max(ext.y).max(0.0) + 2.0 * RASTER_MARGIN;
    let center = nalgebra::center(&floor.min, &floor.max);
    FloorRaster::square(
        center.x - side / 2.0,
        center.y - side / 2.0,
        side,
        RASTER_SIZE,
    )
}

/// The free cells of `grid` before any object: the floor eroded by the robot radius, minus the
/// `walls` grown by it.
pub fn free_floor(grid: &FloorRaster, floor: &Floor, walls: &[WallPiece]) -> Vec<bool> {
    let r = ROBOT_RADIUS;
    let mut free = vec![false; grid.len()];
    for j in 0..grid.nz {
        for i in 0..grid.nx {
            let [x, z] = grid.center(i, j);
            let inside = x - floor.min.x >= r
                && floor.max.x - x >= r
                && z - floor.min.y >= r
                && floor.max.y - z >= r;
            free[j * grid.nx + i] = inside
                && (walls.iter())
                    .filter(|w| w.on_floor())
                    .all(|w| w.rect.distance(x, z) > r);
        }
    }
    free
}

/// The cells of `grid` an obstacle takes: its footprint grown (round) by the robot radius.
pub fn grown_cells(grid: &FloorRaster, rect: &FloorRect) -> Vec<usize> {
    let r = ROBOT_RADIUS;
    let mut px = Vec::new();
    grid.for_cells_where(
        rect.bounds(r),
        |x, z| rect.distance(x, z) <= r,
        |p| px.push(p),
    );
    px
}

/// The walkable components by the Walk metric's rules: the metric's raster of `floor`
/// ([`metric_grid`]), its free floor ([`free_floor`]) minus every obstacle's grown footprint
/// ([`grown_cells`]), split into 8-connected components. The caller picks the obstacles (Walk
/// counts the objects whose box centre is below [`WALK_HEIGHT_LIMIT`]).
pub fn walk_components(
    floor: &Floor,
    walls: &[WallPiece],
    obstacles: &[FloorRect],
) -> (FloorRaster, Components) {
    let grid = metric_grid(floor);
    let mut free = free_floor(&grid, floor, walls);
    for rect in obstacles {
        for p in grown_cells(&grid, rect) {
            free[p] = false;
        }
    }
    let parts = grid.components8(&free);
    (grid, parts)
}

/// Computes Walk and Reach exactly as `metrics.md` defines them.
pub fn walk_and_reach(scene: &EvalScene) -> WalkReach {
    let floor = &scene.architecture.floor;
    let grid = metric_grid(floor);
    // The floor eroded by the robot, minus the walls grown by the robot.
    let free = free_floor(&grid, floor, &wall_pieces(scene));
    // Each object's footprint grown by the robot radius, as pixel indices.
    let grown: Vec<Vec<usize>> = scene
        .objects
        .iter()
        .map(|o| footprint(o).map_or_else(Vec::new, |rect| grown_cells(&grid, &rect)))
        .collect();

    // Walk: only objects whose box centre is below the height limit are obstacles.
    let mut walkable = free.clone();
    for (o, px) in scene.objects.iter().zip(&grown) {
        if o.aabb().center().y < WALK_HEIGHT_LIMIT {
            for &p in px {
                walkable[p] = false;
            }
        }
    }
    let walk_parts = grid.components8(&walkable);
    // Component areas in label order (label k is at index k - 1).
    let areas = &walk_parts.sizes[1..];
    let total: usize = areas.iter().sum();
    let walk = if total == 0 {
        0.0
    } else {
        *areas.iter().max().unwrap_or(&0) as f64 / total as f64
    };

    // Reach: every object is an obstacle.
    let mut reach_free = free;
    for px in &grown {
        for &p in px {
            reach_free[p] = false;
        }
    }
    let reach_parts = grid.components8(&reach_free);
    let reach_areas = &reach_parts.sizes[1..];
    let reach_total: usize = reach_areas.iter().sum();
    let touched: Vec<Vec<usize>> = grown
        .iter()
        .map(|px| {
            grid.touched_labels(px, &reach_parts.labels)
                .into_iter()
                .map(|l| l as usize - 1)
                .collect()
        })
        .collect();
    let reach_over = |members: &[usize]| -> Option<f64> {
        if members.is_empty() {
            return None;
        }
        if reach_total == 0 {
            return Some(0.0);
        }
        let mut count = vec![0usize; reach_areas.len()];
        for &m in members {
            for &c in &touched[m] {
                count[c] += 1;
            }
        }
        Some(
            count
                .iter()
                .zip(reach_areas)
                .map(|(&k, &a)| k as f64 / members.len() as f64 * a as f64 / reach_total as f64)
                .sum(),
        )
    };
    let floor_members: Vec<usize> = (0..scene.objects.len())
        .filter(|&k| scene.objects[k].on_ground())
        .collect();
    let all_members: Vec<usize> = (0..scene.objects.len()).collect();
    let unreachable_floor_objects = floor_members
        .iter()
        .filter(|&&k| touched[k].is_empty())
        .map(|&k| scene.objects[k].id.clone())
        .collect();
    WalkReach {
        walk,
        reach_floor: reach_over(&floor_members),
        reach_all: reach_over(&all_members),
        walkable_area: total as f64 * grid.cell * grid.cell,
        walk_components: areas.len(),
        unreachable_floor_objects,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::piece_depth;
    use nalgebra::Point3;
    use scenethesis_scene_graph::{Architecture, WindowOpening};

    /// A point poking into a window's opening touches nothing unless it reaches the pane; the
    /// wall below the sill and the pane are solid, and only pieces on the floor block walking.
    #[test]
    fn a_window_opening_is_open_but_its_pane_and_sill_are_solid() {
        let mut architecture = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let back = &architecture.walls[0];
        let window = WindowOpening::centred("window_0", back, 1.2, 1.2, 0.9);
        architecture.windows.push(window);
        let scene = EvalScene {
            objects: Vec::new(),
            architecture,
        };
        let pieces = wall_pieces(&scene);
        let hit = |x: f32, y: f32, z: f32| -> Vec<&str> {
            (pieces.iter())
                .filter(|p| piece_depth(p, &[Point3::new(x, y, z)]) > 0.0)
                .map(|p| p.wall.as_str())
                .collect()
        };
        // The back wall's centre line is z = -2.05, its inner face z = -2.0.
        assert!(
            hit(0.0, 1.5, -2.02).is_empty(),
            "in the opening, short of the pane"
        );
        assert_eq!(hit(0.0, 1.5, -2.05), ["window_0"]);
        assert_eq!(hit(0.0, 0.5, -2.02), ["wall_0"], "the wall below the sill");
        assert_eq!(hit(0.0, 2.5, -2.02), ["wall_0"], "the lintel");
        let on_floor: Vec<_> = pieces.iter().filter(|p| p.on_floor()).collect();
        assert!(on_floor
            .iter()
            .all(|p| p.wall != "window_0" && p.bottom == 0.0));
        assert!(pieces.iter().any(|p| p.wall == "wall_0" && !p.on_floor()));
    }
}
