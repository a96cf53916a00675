//! Property tests: lossless JSON round-trips, parent-before-child traversal, and validation
//! that never panics on arbitrary input.

use nalgebra::{Point3, Vector3};
use proptest::prelude::*;
use scenethesis_scene_graph::*;

/// Finite coordinates within `limits::MAX_COORDINATE`, which `validate` enforces.
fn in_limits() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1000.0..1000.0f64,
        -10.0..10.0f64,
        Just(0.0),
        Just(-0.0),
        Just(1e-300)
    ]
}

fn relation_kind() -> impl Strategy<Value = RelationKind> {
    proptest::sample::select(RelationKind::ALL.to_vec())
}

/// A scene of `n` objects whose parent links always point to an earlier object or the ground
/// (so they form a forest), or to a wall for the objects whose support is `mounted`, stored in a
/// random order.
fn forest_scene() -> impl Strategy<Value = Scene> {
    (1usize..24).prop_flat_map(|n| {
        (
            proptest::collection::vec(
                (
                    any::<u32>(),
                    in_limits(),
                    in_limits(),
                    in_limits(),
                    0.01..10.0f64,
                    -7.0..7.0f64,
                    relation_kind(),
                    any::<u64>(),
                ),
                n,
            ),
            Just(n).prop_perturb(|n, mut rng| {
                let mut order: Vec<usize> = (0..n).collect();
                for i in (1..n).rev() {
                    order.swap(i, rng.random_range(0..=i));
                }
                order
            }),
            any::<u64>(),
            "[a-z ]{0,30}",
            proptest::option::of(0usize..24),
        )
            .prop_map(move |(specs, order, seed, prompt, anchor)| {
                let mut objects = Vec::new();
                for (i, (parent_pick, x, y, z, scale, yaw, kind, asset_seed)) in
                    specs.into_iter().enumerate()
                {
                    let parent = if kind == RelationKind::Mounted {
                        ParentRef::Wall(format!("wall_{}", parent_pick % 4))
                    } else if i == 0 || parent_pick % 3 == 0 {
                        ParentRef::Ground
                    } else {
                        ParentRef::Object(format!("obj_{}", parent_pick as usize % i))
                    };
                    let relations = if i > 0 {
                        vec![Relation::new(
                            kind,
                            format!("obj_{}", parent_pick as usize % i),
                        )]
                    } else {
                        vec![Relation::new(RelationKind::AgainstWall, "wall_0")]
                    };
                    objects.push(SceneObject {
                        id: format!("obj_{i}"),
                        category: "crate".into(),
                        asset: if i % 2 == 0 {
                            AssetRef::Procedural {
                                generator: "crate".into(),
                                seed: asset_seed,
                                look: None,
                            }
                        } else {
                            AssetRef::Imported {
                                id: format!("user_{i}"),
                                path: format!("assets/{i}.glb"),
                            }
                        },
                        pose: Pose::new(scale, yaw, Vector3::new(x, y, z)),
                        parent,
                        support: kind,
                        relations,
                        local_bounds: Aabb::new(
                            Point3::new(-0.5, 0.0, -0.25),
                            Point3::new(0.5, x.abs().min(3.0), 0.25),
                        ),
                        joints: Vec::new(),
                        parent_link: None,
                        room: None,
                    });
                }
                let mut scene = Scene::new(Architecture::rectangular_room(8.0, 6.0, 3.0, 1.0));
                scene.seed = seed;
                scene.prompt = prompt;
                scene.anchor = anchor
                    .filter(|a| *a < n)
                    .map(|a| format!("obj_{a}"))
                    .filter(|id| {
                        objects
                            .iter()
                            .any(|o| &o.id == id && o.parent == ParentRef::Ground)
                    });
                scene.objects = order.into_iter().map(|i| objects[i].clone()).collect();
                scene
            })
    })
}

fn arbitrary_json() -> impl Strategy<Value = serde_json::Value> {
    use serde_json::Value;
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        any::<i64>().prop_map(Value::from),
        any::<f64>()
            .prop_filter("finite", |f| f.is_finite())
            .prop_map(Value::from),
        "[a-z_]{0,8}".prop_map(Value::String),
        prop_oneof![
            Just("ground"),
            Just("obj_0"),
            Just("wall_0"),
            Just("on"),
            Just("procedural")
        ]
        .prop_map(|s| Value::String(s.into())),
    ];
    leaf.prop_recursive(4, 64, 8, |inner| {
        prop_oneof![
            proptest::collection::vec(inner.clone(), 0..6).prop_map(Value::Array),
            proptest::collection::btree_map(
                prop_oneof![
                    "[a-z_]{1,8}".boxed(),
                    Just("format_version".to_string()).boxed(),
                    Just("objects".to_string()).boxed(),
                    Just("pose".to_string()).boxed(),
                    Just("parent".to_string()).boxed(),
                    Just("scale".to_string()).boxed(),
                ],
                inner,
                0..6
            )
            .prop_map(|m| Value::Object(m.into_iter().collect())),
        ]
    })
}

/// Replaces the value at a random path of `value` with `replacement`.
fn mutate(value: &mut serde_json::Value, mut path: Vec<usize>, replacement: serde_json::Value) {
    use serde_json::Value;
    let Some(step) = path.pop() else {
        *value = replacement;
        return;
    };
    match value {
        Value::Object(map) if !map.is_empty() => {
            let key = map.keys().nth(step % map.len()).cloned().unwrap();
            if path.is_empty() && step % 7 == 0 {
                map.remove(&key);
            } else {
                mutate(map.get_mut(&key).unwrap(), path, replacement);
            }
        }
        Value::Array(items) if !items.is_empty() => {
            let len = items.len();
            mutate(&mut items[step % len], path, replacement)
        }
        _ => *value = replacement,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn json_round_trip_is_lossless(scene in forest_scene()) {
        let text = scene.to_json_string();
        let back = Scene::from_json_str(&text).unwrap();
        prop_assert_eq!(&back, &scene);
        prop_assert_eq!(back.to_json_string(), text);
    }

    #[test]
    fn bfs_yields_parents_before_children(scene in forest_scene()) {
        prop_assert!(scene.validate().is_ok(), "{:?}", scene.validate());
        let order = scene.bfs_order().unwrap();
        prop_assert_eq!(order.len(), scene.objects.len());
        let position = |id: &str| order.iter().position(|o| o.id == id).unwrap();
        for object in &scene.objects {
            if let Some(parent) = object.parent.object_id() {
                prop_assert!(position(parent) < position(&object.id));
            }
        }
        if let Some(anchor) = &scene.anchor {
            prop_assert_eq!(&order[0].id, anchor);
        }
    }

    #[test]
    fn validation_never_panics_on_arbitrary_json(value in arbitrary_json()) {
        if let Ok(scene) = serde_json::from_value::<Scene>(value) {
            let _ = scene.validate();
            let _ = scene.bfs_order();
        }
    }

    #[test]
    fn validation_never_panics_on_mutated_scenes(
        scene in forest_scene(),
        path in proptest::collection::vec(any::<usize>(), 0..6),
        replacement in arbitrary_json(),
    ) {
        let mut value = serde_json::to_value(&scene).unwrap();
        mutate(&mut value, path, replacement);
        if let Ok(scene) = serde_json::from_value::<Scene>(value) {
            let _ = scene.validate();
            let _ = scene.bfs_order();
            let _ = scene.to_json_string();
        }
    }
}
