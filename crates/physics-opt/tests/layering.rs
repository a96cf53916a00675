//! The optimizer stands below the generators: it needs the asset metadata types, which live in
//! `scenethesis-scene-graph`, not the generators, the importers (with `gltf`) or the metrics.

/// The names of the `[dependencies]` of this crate's manifest (not dev- or build-dependencies).
fn normal_dependencies() -> Vec<String> {
    let manifest = include_str!("../Cargo.toml");
    let mut in_section = false;
    let mut names = Vec::new();
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_section = line == "[dependencies]";
            continue;
        }
        if in_section && !line.is_empty() && !line.starts_with('#') {
            let name = line.split(['=', '.']).next().unwrap_or_default().trim();
            names.push(name.to_owned());
        }
    }
    names
}

#[test]
fn physics_opt_does_not_depend_on_the_generators_or_the_metrics() {
    let deps = normal_dependencies();
    assert!(
        deps.contains(&"scenethesis-scene-graph".to_owned()),
        "{deps:?}"
    );
    for crate_name in [
        "scenethesis-procedural",
        "scenethesis-import",
        "scenethesis-eval",
    ] {
        assert!(
            !deps.iter().any(|d| d == crate_name),
            "physics-opt must not depend on {crate_name}: {deps:?}"
        );
    }
}
