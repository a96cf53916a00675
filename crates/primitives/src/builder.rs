//! The asset builder: parts, materials and support surfaces normalised into an asset.

use std::collections::BTreeSet;

use scenethesis_scene_graph::{
    opening_sweep, Asset, AssetInfo, AssetRef, Joint, Material, Mesh, MeshPart, Placement,
    SupportSurface, SurfaceKind,
};

use crate::{cuboid, rect_surface};

/// Collects parts, materials, support surfaces and joints, then normalises them into an
/// [`Asset`] whose origin is the centre of its footprint at its lowest point.
///
/// Moving parts: add the [`Joint`] with [`AssetBuilder::joint`], then open its link with
/// [`AssetBuilder::link`]; every part added until the link is closed (`link(None)`) moves with
/// that joint (its [`MeshPart::joint`] names it). Parts are drawn closed (state 0).
#[derive(Debug, Default, Clone)]
pub struct AssetBuilder {
    mesh: Mesh,
    surfaces: Vec<SupportSurface>,
    joints: Vec<Joint>,
    /// The joint whose link the parts added now belong to.
    link: Option<String>,
}

impl AssetBuilder {
    /// An empty builder.
    pub fn new() -> Self {
        Self::default()
    }

    /// Flattens the underside into a contact patch: every vertex lower than `depth` above the
    /// parts' lowest point is raised onto that plane. A tessellated sphere or a cylinder lying
    /// on its side otherwise rests on one vertex or edge and rolls off it in simulation (a real
    /// ball or fruit flattens into its contact patch the same way). Convex parts stay convex
    /// while `depth` is below their second ring of vertices.
    pub fn flatten_base(&mut self, depth: f32) {
        let lowest = self
            .mesh
            .parts
            .iter()
            .flat_map(|p| p.positions.iter().map(|v| v[1]))
            .fold(f32::INFINITY, f32::min);
        if !lowest.is_finite() {
            return;
        }
        let plane = lowest + depth;
        for part in &mut self.mesh.parts {
            for v in &mut part.positions {
                v[1] = v[1].max(plane);
            }
        }
    }

    /// Adds `material` (or finds an identical one) and returns its index.
    pub fn material(&mut self, material: Material) -> usize {
        if let Some(i) = self.mesh.materials.iter().position(|m| *m == material) {
            return i;
        }
        self.mesh.materials.push(material);
        self.mesh.materials.len() - 1
    }

    /// Adds a part (its material index must come from [`AssetBuilder::material`]); while a
    /// link is open ([`AssetBuilder::link`]) the part moves with that link's joint.
    pub fn part(&mut self, mut part: MeshPart) -> &mut Self {
        if part.joint.is_none() {
            part.joint.clone_from(&self.link);
        }
        self.mesh.parts.push(part);
        self
    }

    /// Adds an axis-aligned box part (on the open link, as [`AssetBuilder::part`]).
    pub fn cuboid(&mut self, name: &str, material: usize, min: [f32; 3], max: [f32; 3]) {
        self.part(cuboid(name, material, min, max));
    }

    /// Adds a joint (in the same frame as the parts; a parent joint before its children).
    pub fn joint(&mut self, joint: Joint) -> &mut Self {
        self.joints.push(joint);
        self
    }

    /// Opens the link of the joint named `joint` (the parts added next move with it), or
    /// closes it with `None` (the parts added next are fixed to the body).
    pub fn link(&mut self, joint: Option<&str>) -> &mut Self {
        self.link = joint.map(str::to_owned);
        self
    }

    /// The joints added so far.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Adds a support surface (in the same frame as the parts).
    pub fn surface(&mut self, surface: SupportSurface) -> &mut Self {
        self.surfaces.push(surface);
        self
    }

    /// Adds an upward-facing support surface open above (a table top, a seat, a counter) over
    /// the axis-aligned rectangle `min`..`max` in (x, z), shrunk by `margin` as in
    /// [`rect_surface`].
    pub fn top_surface(
        &mut self,
        name: &str,
        min: [f32; 2],
        max: [f32; 2],
        height: f32,
        margin: f32,
    ) -> &mut Self {
        self.surface(rect_surface(
            name,
            SurfaceKind::Top,
            min,
            max,
            height,
            None,
            margin,
        ))
    }

    /// The support surfaces added so far, to adjust them after later parts.
    pub fn surfaces_mut(&mut self) -> &mut Vec<SupportSurface> {
        &mut self.surfaces
    }

    /// Turns everything added so far by half a turn about the vertical axis through `pivot`
    /// = (x, z), e.g. to make compartments built facing +Z open toward −Z.
    pub fn turn_around(&mut self, pivot: [f32; 2]) {
        for part in &mut self.mesh.parts {
            for p in &mut part.positions {
                p[0] = 2.0 * pivot[0] - p[0];
                p[2] = 2.0 * pivot[1] - p[2];
            }
        }
        for s in &mut self.surfaces {
            for p in &mut s.polygon {
                p[0] = 2.0 * pivot[0] - p[0];
                p[1] = 2.0 * pivot[1] - p[1];
            }
        }
        for j in &mut self.joints {
            j.anchor[0] = 2.0 * pivot[0] - j.anchor[0];
            j.anchor[2] = 2.0 * pivot[1] - j.anchor[2];
            j.axis[0] = -j.axis[0];
            j.axis[2] = -j.axis[2];
        }
    }

    /// The parts added so far.
    pub fn parts(&self) -> &[MeshPart] {
        &self.mesh.parts
    }

    /// Moves everything so that the footprint centre at the lowest point is the origin, and
    /// returns the asset with its size from the mesh bounds. `source`, `category` and
    /// `synonyms` are left for the registry that calls the generator to fill in
    /// (`scenethesis_procedural::catalog::generate`).
    ///
    /// # Panics
    /// When no part was added, or the joints are malformed (a generator bug): a joint that
    /// fails [`Joint::check`], two joints of one name, a joint without parts, a parent joint
    /// unknown or listed after its child, or a part naming an unknown joint.
    pub fn finish(mut self, placement: Placement, scale_range: [f32; 2]) -> Asset {
        self.check_joints();
        let bounds = self
            .mesh
            .bounds()
            .expect("an asset needs at least one part");
        let (min, max) = (bounds.min.cast::<f32>(), bounds.max.cast::<f32>());
        let shift = [-0.5 * (min.x + max.x), -min.y, -0.5 * (min.z + max.z)];
        for part in &mut self.mesh.parts {
            for p in &mut part.positions {
                for k in 0..3 {
                    p[k] += shift[k];
                }
            }
        }
        for s in &mut self.surfaces {
            for p in &mut s.polygon {
                p[0] += shift[0];
                p[1] += shift[2];
            }
            s.height += shift[1];
        }
        for j in &mut self.joints {
            for (a, d) in j.anchor.iter_mut().zip(shift) {
                *a += d;
            }
        }
        let size = max - min;
        Asset {
            info: AssetInfo {
                source: AssetRef::Procedural {
                    generator: String::new(),
                    seed: 0,
                    look: None,
                },
                category: String::new(),
                synonyms: Vec::new(),
                size: [size.x, size.y, size.z],
                placement,
                front: [0.0, 0.0, 1.0],
                support_surfaces: self.surfaces,
                scale_range,
                opening_bounds: opening_sweep(&self.mesh, &self.joints),
                joints: self.joints,
            },
            mesh: self.mesh,
        }
    }

    /// Panics naming the first malformed joint (see [`AssetBuilder::finish`]).
    fn check_joints(&self) {
        let mut seen = BTreeSet::new();
        for j in &self.joints {
            if let Err(e) = j.check() {
                panic!("generator bug: {e}");
            }
            if let Some(parent) = &j.parent {
                assert!(
                    seen.contains(parent.as_str()),
                    "generator bug: joint `{}`: parent `{parent}` is not a joint listed before it",
                    j.name
                );
            }
            assert!(
                seen.insert(j.name.as_str()),
                "generator bug: two joints are named `{}`",
                j.name
            );
            assert!(
                self.mesh
                    .parts
                    .iter()
                    .any(|p| p.joint.as_deref() == Some(j.name.as_str())),
                "generator bug: joint `{}` moves no part",
                j.name
            );
        }
        for p in &self.mesh.parts {
            if let Some(name) = &p.joint {
                assert!(
                    seen.contains(name.as_str()),
                    "generator bug: part `{}` moves with unknown joint `{name}`",
                    p.name
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::{JointKind, OpensTo};

    fn lid() -> Joint {
        Joint {
            name: "lid".into(),
            kind: JointKind::Revolute,
            axis: [-1.0, 0.0, 0.0],
            anchor: [2.0, 1.0, 3.0],
            limits: [0.0, 1.5],
            opens_to: OpensTo::Up,
            parent: None,
        }
    }

    #[test]
    fn joints_move_with_the_mesh_and_link_their_parts() {
        let mut b = AssetBuilder::new();
        b.cuboid("body", 0, [1.0, 0.5, 2.0], [3.0, 1.0, 3.0]);
        b.joint(lid()).link(Some("lid"));
        b.cuboid("lid", 0, [1.0, 1.0, 2.0], [3.0, 1.1, 3.0]);
        b.link(None);
        b.turn_around([2.0, 2.5]);
        let asset = b.finish(Placement::Floor, [1.0, 1.0]);
        let j = &asset.info.joints[0];
        // Turned about (2, 2.5): the back edge z = 3 comes to z = 2; recentred on the
        // footprint (x 1..3, z 2..3) and the lowest point y = 0.5.
        assert_eq!(j.anchor, [0.0, 0.5, -0.5]);
        assert_eq!(j.axis, [1.0, 0.0, 0.0]);
        assert_eq!(asset.mesh.parts[0].joint, None);
        assert_eq!(asset.mesh.parts[1].joint.as_deref(), Some("lid"));
    }

    #[test]
    #[should_panic(expected = "joint `lid` moves no part")]
    fn a_joint_without_parts_is_a_generator_bug() {
        let mut b = AssetBuilder::new();
        b.cuboid("body", 0, [0.0; 3], [1.0; 3]);
        b.joint(lid());
        b.finish(Placement::Floor, [1.0, 1.0]);
    }

    #[test]
    #[should_panic(expected = "unknown joint `door`")]
    fn a_part_of_an_unknown_joint_is_a_generator_bug() {
        let mut b = AssetBuilder::new();
        b.link(Some("door"));
        b.cuboid("door", 0, [0.0; 3], [1.0; 3]);
        b.finish(Placement::Floor, [1.0, 1.0]);
    }
}
