//! Crate-wide checks over every registered category: the names match the documented list,
//! every part is a closed, outward-oriented solid, generation is deterministic per seed and
//! varies across seeds, sizes stay inside the documented ranges, metadata is consistent with
//! the mesh, and every support surface really holds a small box (checked against the asset's
//! signed distance field).

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_procedural::catalog::{self, Category};
use scenethesis_scene_graph::nalgebra::Point3;
use scenethesis_scene_graph::{Placement, SupportSurface, SurfaceKind};
use scenethesis_sdf::{MeshSdf, SignedDistance};

/// Seeds every structural check runs over.
const SEEDS: [u64; 4] = [0, 1, 7, 1234];

fn all() -> Vec<&'static Category> {
    catalog::categories().collect()
}

/// Category names and placement letters from the table in docs/asset-categories.md.
fn documented() -> BTreeMap<String, String> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/asset-categories.md"
    );
    let text = std::fs::read_to_string(path).expect("read docs/asset-categories.md");
    let mut names = BTreeMap::new();
    for line in text
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| group"))
    {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let (group, list) = (cells[1], cells[2]);
        let letters = group
            .split('(')
            .nth(1)
            .expect("group cell names its placement in parentheses")
            .trim_end_matches(')')
            .to_owned();
        for name in list.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            names.insert(name.to_owned(), letters.clone());
        }
    }
    names
}

#[test]
fn registry_matches_the_documented_category_list() {
    let docs = documented();
    let registered: BTreeSet<&str> = all().iter().map(|c| c.name).collect();
    assert_eq!(registered.len(), all().len(), "duplicate category names");
    let documented: BTreeSet<&str> = docs.keys().map(String::as_str).collect();
    let missing: Vec<_> = documented.difference(&registered).collect();
    let extra: Vec<_> = registered.difference(&documented).collect();
    assert!(
        missing.is_empty(),
        "documented but not registered: {missing:?}"
    );
    assert!(extra.is_empty(), "registered but not documented: {extra:?}");
    for c in all() {
        let letter = match c.placement {
            Placement::Floor => "F",
            Placement::Surface => "S",
            Placement::Wall => "W",
            Placement::Ceiling => "C",
        };
        let allowed = &docs[c.name];
        assert!(
            allowed.split(" or ").any(|l| l == letter),
            "{}: placement {letter}, documented {allowed}",
            c.name
        );
        assert!(
            c.synonyms.iter().all(|s| !s.is_empty() && *s != c.name),
            "{}: bad synonym",
            c.name
        );
    }
    // A synonym names one category only, and never another category.
    let mut owner: BTreeMap<String, &str> = BTreeMap::new();
    for c in all() {
        for s in c.synonyms {
            let key = s.replace(' ', "_");
            assert!(
                !registered.contains(key.as_str()) || key == c.name,
                "{}: synonym `{s}` is another category's name",
                c.name
            );
            if let Some(other) = owner.insert(s.to_string(), c.name) {
                panic!("synonym `{s}` is shared by {other} and {}", c.name);
            }
        }
    }
    assert!(all().len() >= 80, "only {} categories", all().len());
}

/// Also checks (sharing the generation) that every material an asset uses wears a material of
/// the texture library, so that no generated surface is exported untextured.
#[test]
fn every_part_is_a_closed_outward_solid() {
    let mut unmapped = BTreeSet::new();
    for c in all() {
        for seed in SEEDS {
            let asset = catalog::generate(c, seed);
            for m in &asset.mesh.materials {
                if scenethesis_materials::resolve(&m.name).is_none() {
                    unmapped.insert(format!("{} ({})", m.name, c.name));
                }
            }
            assert!(!asset.mesh.parts.is_empty(), "{} #{seed}: no parts", c.name);
            let mut names = BTreeSet::new();
            for part in &asset.mesh.parts {
                assert!(
                    part.is_closed_and_oriented(),
                    "{} #{seed}: part `{}` is not closed and consistently oriented",
                    c.name,
                    part.name
                );
                let volume = part.signed_volume();
                assert!(
                    volume > 1e-9,
                    "{} #{seed}: part `{}` has volume {volume}",
                    c.name,
                    part.name
                );
                assert!(
                    part.material < asset.mesh.materials.len(),
                    "{} #{seed}: part `{}` material",
                    c.name,
                    part.name
                );
                assert!(
                    part.positions.iter().flatten().all(|v| v.is_finite()),
                    "{} #{seed}: part `{}` has a non-finite vertex",
                    c.name,
                    part.name
                );
                assert!(
                    names.insert(part.name.clone()),
                    "{} #{seed}: duplicate part name `{}`",
                    c.name,
                    part.name
                );
            }
            for m in &asset.mesh.materials {
                let in_unit = |v: f32| (0.0..=1.0).contains(&v);
                assert!(
                    m.base_color.iter().all(|&v| in_unit(v))
                        && in_unit(m.roughness)
                        && in_unit(m.metallic),
                    "{} #{seed}: material {} out of range",
                    c.name,
                    m.name
                );
            }
        }
    }
    assert!(
        unmapped.is_empty(),
        "material names without a texture-library material (add them to scenethesis-materials' \
         resolve tables): {unmapped:?}"
    );
}

#[test]
fn generation_is_deterministic_per_seed() {
    for c in all() {
        for seed in [3, 99] {
            assert_eq!(
                catalog::generate(c, seed),
                catalog::generate(c, seed),
                "{} #{seed}",
                c.name
            );
        }
    }
}

#[test]
fn seeds_vary_dimensions_and_materials() {
    // Some categories are standardised in one respect (a billiard ball's diameter, a glass
    // beaker's material), so each category must vary in size or in materials, and over 8
    // seeds give at least 4 visibly different assets.
    let mut unvaried = Vec::new();
    for c in all() {
        let variants: BTreeSet<(Vec<u32>, Vec<u32>)> = (0..8)
            .map(|s| catalog::generate(c, s))
            .map(|a| {
                let size = a.info.size.map(f32::to_bits).to_vec();
                // The material list and the colour each part wears.
                let list = a.mesh.materials.iter().map(|m| m.base_color);
                let worn = a
                    .mesh
                    .parts
                    .iter()
                    .map(|p| a.mesh.materials[p.material].base_color);
                let palette = list.chain(worn).flat_map(|c| c.map(f32::to_bits)).collect();
                (size, palette)
            })
            .collect();
        if variants.len() < 4 {
            unvaried.push((c.name, variants.len()));
        }
    }
    assert!(
        unvaried.is_empty(),
        "categories with fewer than 4 distinct assets over 8 seeds: {unvaried:?}"
    );
}

#[test]
fn sizes_stay_inside_the_documented_ranges() {
    let mut failures = Vec::new();
    for c in all() {
        for seed in 0..24 {
            let size = catalog::generate(c, seed).info.size;
            for (axis, (s, [lo, hi])) in size.iter().zip(c.size_range).enumerate() {
                assert!(lo <= hi && lo > 0.0, "{}: bad documented range", c.name);
                if *s < lo - 1e-3 || *s > hi + 1e-3 {
                    failures.push(format!(
                        "{} #{seed}: size[{axis}] = {s:.3} outside [{lo}, {hi}]",
                        c.name
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn metadata_agrees_with_the_mesh() {
    for c in all() {
        for seed in SEEDS {
            let asset = catalog::generate(c, seed);
            let info = &asset.info;
            let who = format!("{} #{seed}", c.name);
            assert_eq!(info.category, c.name);
            assert_eq!(info.placement, c.placement, "{who}");
            assert_eq!(info.front, [0.0, 0.0, 1.0], "{who}");
            assert!(
                info.scale_range[0] > 0.0
                    && info.scale_range[0] <= 1.0
                    && info.scale_range[1] >= 1.0,
                "{who}"
            );
            let b = asset.mesh.bounds().expect("bounds");
            let size = b.size();
            for k in 0..3 {
                assert!(
                    (size[k] as f32 - info.size[k]).abs() < 1e-4,
                    "{who}: size[{k}]"
                );
            }
            // Origin: footprint centre at the lowest point.
            assert!(
                b.min.y.abs() < 1e-5,
                "{who}: lowest point at y = {}",
                b.min.y
            );
            assert!(
                (b.min.x + b.max.x).abs() < 1e-4,
                "{who}: footprint not centred in x"
            );
            assert!(
                (b.min.z + b.max.z).abs() < 1e-4,
                "{who}: footprint not centred in z"
            );
            let mut names = BTreeSet::new();
            for s in &info.support_surfaces {
                assert!(
                    names.insert(s.name.clone()),
                    "{who}: duplicate surface `{}`",
                    s.name
                );
                check_polygon(&who, s);
                let [cx, cz] = s.center();
                assert!(
                    (b.min.x as f32..=b.max.x as f32).contains(&cx)
                        && (b.min.z as f32..=b.max.z as f32).contains(&cz),
                    "{who}: surface `{}` centre outside the footprint",
                    s.name
                );
                assert!(
                    (0.0..=info.size[1] + 1e-4).contains(&s.height),
                    "{who}: surface `{}` height {}",
                    s.name,
                    s.height
                );
                if s.kind == SurfaceKind::Under {
                    assert!(
                        s.height.abs() < 1e-5,
                        "{who}: `under` surfaces are on the floor"
                    );
                    assert!(s.clearance.is_some(), "{who}: `under` needs a clearance");
                }
                if let Some(cl) = s.clearance {
                    assert!(cl > 0.0, "{who}: surface `{}` clearance {cl}", s.name);
                }
            }
        }
    }
}

/// The polygon is convex, counter-clockwise seen from above (negative shoelace sum in (x, z),
/// since +Z points toward the viewer's bottom), and not degenerate.
fn check_polygon(who: &str, s: &SupportSurface) {
    let p = &s.polygon;
    assert!(
        p.len() >= 3,
        "{who}: surface `{}` has {} corners",
        s.name,
        p.len()
    );
    let n = p.len();
    let twice: f32 = (0..n)
        .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
        .sum();
    assert!(
        twice < 0.0,
        "{who}: surface `{}` is not counter-clockwise seen from above",
        s.name
    );
    assert!(s.area() > 1e-5, "{who}: surface `{}` is degenerate", s.name);
    let [cx, cz] = s.center();
    assert!(
        s.contains(cx, cz),
        "{who}: surface `{}` is not convex around its centre",
        s.name
    );
}

/// Distance from (x, z) to the nearest polygon edge.
fn inradius_at(s: &SupportSurface, x: f32, z: f32) -> f32 {
    let n = s.polygon.len();
    (0..n)
        .map(|i| {
            let (a, b) = (s.polygon[i], s.polygon[(i + 1) % n]);
            let (ex, ez) = (b[0] - a[0], b[1] - a[1]);
            let len = (ex * ex + ez * ez).sqrt().max(1e-9);
            ((x - a[0]) * ez - (z - a[1]) * ex).abs() / len
        })
        .fold(f32::INFINITY, f32::min)
}

/// A small box dropped at the centre of every support surface rests on something solid, does
/// not penetrate the asset, and the column above it is free up to the stated clearance.
#[test]
fn a_small_box_rests_on_every_support_surface() {
    let mut failures = Vec::new();
    for c in all() {
        for seed in [0, 1, 7] {
            let asset = catalog::generate(c, seed);
            if asset.info.support_surfaces.is_empty() {
                continue;
            }
            let sdf = MeshSdf::from_mesh(&asset.mesh).expect("sdf of a generated asset");
            for s in &asset.info.support_surfaces {
                let who = format!("{} #{seed} `{}`", c.name, s.name);
                let [cx, cz] = s.center();
                let room = inradius_at(s, cx, cz);
                let cap = s.clearance.unwrap_or(f32::INFINITY);
                let side = 0.05f32.min(1.2 * room).min(0.9 * cap);
                if side < 0.01 {
                    failures.push(format!(
                        "{who}: holds no 1 cm cube (room {room:.3}, clearance {cap:.3})"
                    ));
                    continue;
                }
                assert!(side <= cap, "{who}");
                // Something solid right under the surface (except the floor under furniture).
                if s.kind != SurfaceKind::Under {
                    // The centre and four points 3 mm around it, so that a centre lying exactly
                    // on the shared face of two touching parts still finds them.
                    let below = [
                        (0.0, 0.0),
                        (0.003, 0.0),
                        (-0.003, 0.0),
                        (0.0, 0.003),
                        (0.0, -0.003),
                    ]
                    .iter()
                    .map(|(dx, dz)| sdf.distance(&Point3::new(cx + dx, s.height - 0.001, cz + dz)))
                    .fold(f32::INFINITY, f32::min);
                    if below >= 0.0 {
                        failures.push(format!(
                            "{who}: nothing solid under the surface (sdf {below:.4})"
                        ));
                    }
                }
                // The box itself: a 5×5×5 lattice of points.
                let h = 0.5 * side;
                let mut worst = f32::INFINITY;
                for i in 0..5 {
                    for j in 0..5 {
                        for k in 0..5 {
                            let f = |t: usize| t as f32 / 4.0;
                            let p = Point3::new(
                                cx - h + side * f(i),
                                s.height + 0.0005 + (side - 0.0005) * f(j),
                                cz - h + side * f(k),
                            );
                            worst = worst.min(sdf.distance(&p));
                        }
                    }
                }
                if worst < -0.001 {
                    failures.push(format!(
                        "{who}: a {side:.3} m box penetrates by {:.4} m",
                        -worst
                    ));
                }
                // The column above the centre is free up to the clearance (or the asset's top).
                let top = s
                    .clearance
                    .map_or(asset.info.size[1] + 0.05, |cl| s.height + cl);
                let steps = 40;
                for t in 0..=steps {
                    let y = s.height
                        + 0.002
                        + (top - 0.002 - s.height - 0.002) * t as f32 / steps as f32;
                    let d = sdf.distance(&Point3::new(cx, y, cz));
                    if d < -0.001 {
                        failures.push(format!(
                            "{who}: solid at y = {y:.3} inside the clearance (sdf {d:.4})"
                        ));
                        break;
                    }
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn furniture_has_real_cavities_where_the_method_needs_them() {
    let kinds = |name: &str| -> Vec<SurfaceKind> {
        let c = catalog::category(name).expect(name);
        catalog::generate(c, 0)
            .info
            .support_surfaces
            .iter()
            .map(|s| s.kind)
            .collect()
    };
    for name in [
        "bookshelf",
        "display_shelf",
        "store_shelf",
        "cabinet",
        "locker",
        "wardrobe",
        "display_case",
        "pallet_rack",
        "shelving_unit",
        "refrigerator",
        "drinks_fridge",
        "fume_hood",
    ] {
        let shelves = kinds(name)
            .iter()
            .filter(|k| **k == SurfaceKind::Shelf)
            .count();
        assert!(shelves >= 1, "{name}: no shelf compartment");
    }
    for name in ["dining_table", "desk", "bench", "lab_bench"] {
        assert!(
            kinds(name).contains(&SurfaceKind::Under),
            "{name}: nothing fits under it"
        );
    }
    for name in ["toy_box", "chest_freezer", "sink"] {
        assert!(
            kinds(name).contains(&SurfaceKind::Interior),
            "{name}: not open on top"
        );
    }
    // A bookshelf compartment is at least 0.25 m clear and several compartments deep.
    let shelf = catalog::generate(catalog::category("bookshelf").unwrap(), 0);
    let compartments: Vec<&SupportSurface> = shelf
        .info
        .support_surfaces
        .iter()
        .filter(|s| s.kind == SurfaceKind::Shelf)
        .collect();
    assert!(compartments.len() >= 4);
    assert!(compartments.iter().all(|s| s.clearance.unwrap() >= 0.24));
}
