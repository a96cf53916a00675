//! `scenethesis validate`: check a scene.json and print its placement order.

use std::path::PathBuf;

use anyhow::{Context, Result};
use scenethesis_scene_graph::{Scene, SceneIoError};

/// Validates `path` (a scene.json, or a folder holding one) and prints a summary.
pub fn run(path: PathBuf) -> Result<()> {
    let file = if path.is_dir() {
        path.join("scene.json")
    } else {
        path
    };
    tracing::info!(file = %file.display(), "validating");
    let scene = match Scene::read_json(&file) {
        Ok(scene) => scene,
        Err(SceneIoError::Invalid { all, .. }) if all.len() > 1 => {
            for problem in &all {
                eprintln!("  - {problem}");
            }
            return Err(anyhow::anyhow!(
                "{} describes an invalid scene ({} problems, listed above)",
                file.display(),
                all.len()
            ));
        }
        Err(err) => return Err(err).context("validation failed"),
    };
    let unknown =
        scene.generator_errors(|g| scenethesis_procedural::catalog::category(g).is_some());
    if !unknown.is_empty() {
        for problem in &unknown {
            eprintln!("  - {problem}");
        }
        return Err(anyhow::anyhow!(
            "{} names {} unknown procedural generator(s), listed above",
            file.display(),
            unknown.len()
        ));
    }
    let order = scene.bfs_order().context("cannot order the scene graph")?;
    let ids: Vec<String> = order
        .iter()
        .map(|o| scenethesis_scene_graph::printable(&o.id).into_owned())
        .collect();
    println!(
        "{}: valid scene, {} objects, anchor {}, {} walls, {} doors",
        file.display(),
        scene.objects.len(),
        scenethesis_scene_graph::printable(scene.anchor.as_deref().unwrap_or("(none)")),
        scene.architecture.walls.len(),
        scene.architecture.doors.len()
    );
    println!("placement order: {}", ids.join(" → "));
    Ok(())
}
