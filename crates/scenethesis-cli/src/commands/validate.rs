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
    let order = scene.bfs_order().context("cannot order the scene graph")?;
    let ids: Vec<&str> = order.iter().map(|o| o.id.as_str()).collect();
    println!(
        "{}: valid scene, {} objects, anchor {}, {} walls, {} doors",
        file.display(),
        scene.objects.len(),
        scene.anchor.as_deref().unwrap_or("(none)"),
        scene.architecture.walls.len(),
        scene.architecture.doors.len()
    );
    println!("placement order: {}", ids.join(" → "));
    Ok(())
}
