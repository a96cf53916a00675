//! Byte-level regression guard for the procedural generators: every category's assets for seeds
//! 0..4 are folded into a 64-bit FNV-1a digest (vertex positions as f32 bits, triangle indices,
//! part names, materials and joints, material names and colours, size, scale range, support
//! surfaces and joints) and compared with the digests stored in `catalog_digest.txt`. A refactoring of the
//! generators must leave every digest unchanged. After an intended change to the generated
//! geometry, rewrite the file with `SCENETHESIS_BLESS=1 cargo test -p scenethesis-procedural --test
//! catalog_digest` and review the diff.

use std::collections::BTreeMap;

use scenethesis_procedural::catalog;
use scenethesis_scene_graph::{Asset, SurfaceKind};

/// Seeds whose assets are digested for every category.
const SEEDS: std::ops::Range<u64> = 0..4;

/// The stored digests, one `category seed digest` line each.
const DIGEST_FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/catalog_digest.txt");

/// 64-bit FNV-1a over everything written into it.
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn u32(&mut self, v: u32) {
        self.bytes(&v.to_le_bytes());
    }

    fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }

    /// A length-prefixed string, so that adjacent strings cannot run into each other.
    fn str(&mut self, s: &str) {
        self.u32(s.len() as u32);
        self.bytes(s.as_bytes());
    }
}

fn digest(asset: &Asset) -> u64 {
    let mut h = Fnv1a::new();
    let mesh = &asset.mesh;
    h.u32(mesh.materials.len() as u32);
    for m in &mesh.materials {
        h.str(&m.name);
        m.base_color.iter().for_each(|&c| h.f32(c));
        h.f32(m.roughness);
        h.f32(m.metallic);
    }
    h.u32(mesh.parts.len() as u32);
    for part in &mesh.parts {
        h.str(&part.name);
        h.u32(part.material as u32);
        h.u32(part.positions.len() as u32);
        part.positions.iter().flatten().for_each(|&v| h.f32(v));
        h.u32(part.triangles.len() as u32);
        part.triangles.iter().flatten().for_each(|&i| h.u32(i));
        // Folded only when set, so that the digests of assets without joints stay as they were.
        if let Some(joint) = &part.joint {
            h.str(joint);
        }
    }
    let info = &asset.info;
    info.size.iter().for_each(|&v| h.f32(v));
    info.scale_range.iter().for_each(|&v| h.f32(v));
    h.u32(info.support_surfaces.len() as u32);
    for s in &info.support_surfaces {
        h.str(&s.name);
        h.u32(match s.kind {
            SurfaceKind::Top => 0,
            SurfaceKind::Shelf => 1,
            SurfaceKind::Interior => 2,
            SurfaceKind::Under => 3,
        });
        h.u32(s.polygon.len() as u32);
        s.polygon.iter().flatten().for_each(|&v| h.f32(v));
        h.f32(s.height);
        match s.clearance {
            Some(c) => {
                h.u32(1);
                h.f32(c);
            }
            None => h.u32(0),
        }
    }
    if !info.joints.is_empty() {
        h.u32(info.joints.len() as u32);
    }
    for j in &info.joints {
        h.str(&j.name);
        h.str(&format!("{:?} {:?} {:?}", j.kind, j.opens_to, j.parent));
        j.axis
            .iter()
            .chain(&j.anchor)
            .chain(&j.limits)
            .for_each(|&v| h.f32(v));
    }
    h.0
}

/// `category seed` → digest of the current generators.
fn current() -> BTreeMap<(String, u64), u64> {
    let mut out = BTreeMap::new();
    for c in catalog::categories() {
        for seed in SEEDS {
            out.insert(
                (c.name.to_owned(), seed),
                digest(&catalog::generate(c, seed)),
            );
        }
    }
    out
}

fn render(digests: &BTreeMap<(String, u64), u64>) -> String {
    digests
        .iter()
        .map(|((name, seed), d)| format!("{name} {seed} {d:016x}\n"))
        .collect()
}

#[test]
fn generated_assets_match_the_stored_digests() {
    let now = current();
    if std::env::var_os("SCENETHESIS_BLESS").is_some() {
        std::fs::write(DIGEST_FILE, render(&now)).expect("write catalog_digest.txt");
        return;
    }
    let stored = std::fs::read_to_string(DIGEST_FILE).expect(
        "read tests/catalog_digest.txt (create it with SCENETHESIS_BLESS=1 after checking the \
         generators)",
    );
    let now_text = render(&now);
    let changed: Vec<String> = stored
        .lines()
        .zip(now_text.lines())
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("stored {a}  now {b}"))
        .collect();
    assert_eq!(
        stored.lines().count(),
        now_text.lines().count(),
        "the set of categories changed; re-bless after review"
    );
    assert!(
        changed.is_empty(),
        "{} generated assets changed:\n{}",
        changed.len(),
        changed.join("\n")
    );
}

#[test]
fn the_digest_sees_a_one_ulp_vertex_change() {
    let c = catalog::category("dining_table").expect("dining_table is registered");
    let asset = catalog::generate(c, 0);
    let mut nudged = asset.clone();
    let v = &mut nudged.mesh.parts[0].positions[0][1];
    *v = f32::from_bits(v.to_bits() + 1);
    assert_ne!(digest(&asset), digest(&nudged));
}
