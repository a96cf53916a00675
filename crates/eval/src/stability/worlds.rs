//! Splitting a scene's free bodies into groups that cannot touch during a settle, so that each
//! group is simulated in a world of its own, the worlds side by side on the spare cores.
//!
//! Two free bodies only act on each other through contacts, directly or through other free
//! bodies (the floor, the walls and the welded objects are fixed: they never carry a push from
//! one body to another). Bodies whose boxes are more than [`WORLD_GAP`] apart, and not joined
//! through a chain of nearer neighbours, cannot meet unless one of them travels a good part of
//! that gap; the simulation checks that none did ([`MAX_EXCURSION`]) and otherwise runs the
//! whole scene in one world again.

use scenethesis_scene_graph::Aabb;

/// Free bodies whose boxes are farther apart than this (m), on every axis where they do not
/// overlap, and not joined through nearer bodies, may be simulated in separate worlds.
pub const WORLD_GAP: f64 = 0.05;

/// The farthest (m) any point of a body may travel during a simulation in separate worlds for
/// its result to stand: two bodies of different worlds then stay more than `WORLD_GAP − 2 ×
/// MAX_EXCURSION` = 1 cm apart, beyond the contact prediction distance (2 mm), so neither
/// could have touched the other. A scene where a body travels farther is simulated again in
/// one world.
pub const MAX_EXCURSION: f64 = 0.02;

/// The most worlds a scene is split into. Every world steps the room and the welded objects
/// too, so more worlds cost more in all: two side by side took 40 % less time than one world
/// on two cores, and four only 31 % less. A fixed number rather than the machine's core count:
/// the split changes the results by rounding, and a scene must come out the same everywhere.
pub const MAX_WORLDS: usize = 2;

/// One free body to place in a world: its box (world frame) and a weight for balancing the
/// worlds (its number of colliders).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FreeBody {
    /// The body's box.
    pub bounds: Aabb,
    /// What simulating the body costs, roughly: its number of colliders.
    pub weight: usize,
}

/// Whether two boxes come within `gap` of each other.
fn near(a: &Aabb, b: &Aabb, gap: f64) -> bool {
    (0..3).all(|k| a.min[k] - gap <= b.max[k] && b.min[k] - gap <= a.max[k])
}

/// The groups of bodies joined by chains of boxes within [`WORLD_GAP`] of each other, each a
/// list of body indices in increasing order, the groups ordered by their first body.
pub(crate) fn touching_groups(bodies: &[FreeBody]) -> Vec<Vec<usize>> {
    let mut root: Vec<usize> = (0..bodies.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for i in 0..bodies.len() {
        for j in i + 1..bodies.len() {
            if near(&bodies[i].bounds, &bodies[j].bounds, WORLD_GAP) {
                let (a, b) = (find(&mut root, i), find(&mut root, j));
                root[a.max(b)] = a.min(b);
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut group_of_root = vec![usize::MAX; bodies.len()];
    for i in 0..bodies.len() {
        let r = find(&mut root, i);
        if group_of_root[r] == usize::MAX {
            group_of_root[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[group_of_root[r]].push(i);
    }
    groups
}

/// The bodies shared out over at most [`MAX_WORLDS`] worlds: each touching group whole, the
/// heaviest group first into the lightest world so far (ties to the earlier one), each world's
/// bodies in increasing order, heaviest world first. Empty worlds are left out.
pub(crate) fn worlds(bodies: &[FreeBody]) -> Vec<Vec<usize>> {
    let weight = |group: &[usize]| group.iter().map(|&i| bodies[i].weight).sum::<usize>();
    let mut groups = touching_groups(bodies);
    // Stable: equal weights keep the order of their first body.
    groups.sort_by_key(|g| std::cmp::Reverse(weight(g)));
    let mut worlds: Vec<(usize, Vec<usize>)> = vec![(0, Vec::new()); MAX_WORLDS];
    for group in groups {
        let lightest = (0..MAX_WORLDS)
            .min_by_key(|&w| (worlds[w].0, w))
            .unwrap_or(0);
        worlds[lightest].0 += weight(&group);
        worlds[lightest].1.extend(group);
    }
    worlds.retain(|(_, members)| !members.is_empty());
    worlds.sort_by_key(|(w, _)| std::cmp::Reverse(*w));
    worlds
        .into_iter()
        .map(|(_, mut members)| {
            members.sort_unstable();
            members
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    fn body(x: f64, width: f64, weight: usize) -> FreeBody {
        FreeBody {
            bounds: Aabb::new(Point3::new(x, 0.0, 0.0), Point3::new(x + width, 1.0, 1.0)),
            weight,
        }
    }

    #[test]
    fn bodies_within_the_gap_share_a_group_through_chains() {
        // 0 and 1 are 4 cm apart, 1 and 2 touch, 3 is 6 cm from 2.
        let bodies = [
            body(0.0, 1.0, 1),
            body(1.04, 1.0, 1),
            body(2.04, 0.5, 1),
            body(2.6, 1.0, 1),
        ];
        assert_eq!(touching_groups(&bodies), vec![vec![0, 1, 2], vec![3]]);
        // Apart on one axis is enough: the same boxes side by side in depth.
        let mut far = body(0.5, 1.0, 1);
        far.bounds.min.z = 1.06;
        far.bounds.max.z = 2.0;
        assert_eq!(touching_groups(&[bodies[0], far]).len(), 2);
    }

    #[test]
    fn worlds_balance_the_weights_and_keep_groups_whole() {
        // Groups of weight 9 (bodies 0, 1), 5, 4, 3, 2 and 1, each 1 m apart.
        let weights = [[4, 5], [5, 0], [4, 0], [3, 0], [2, 0], [1, 0]];
        let mut bodies = Vec::new();
        for (k, w) in weights.iter().enumerate() {
            bodies.push(body(3.0 * k as f64, 1.0, w[0]));
            if w[1] > 0 {
                bodies.push(body(3.0 * k as f64 + 1.0, 1.0, w[1]));
            }
        }
        let split = worlds(&bodies);
        assert_eq!(MAX_WORLDS, 2, "the expected split below is for two worlds");
        // 9 and 5 open the two worlds; 4 joins the 5, 3 the first of the two 9s, then 2 and
        // 1 the lighter world: 12 and 12.
        assert_eq!(split, vec![vec![0, 1, 4], vec![2, 3, 5, 6]]);
        let load: Vec<usize> = split
            .iter()
            .map(|w| w.iter().map(|&i| bodies[i].weight).sum())
            .collect();
        assert_eq!(load, vec![12, 12]);
        // One group stays one world.
        assert_eq!(worlds(&bodies[..2]), vec![vec![0, 1]]);
    }
}
