//! A photo alone: with no prompt, the scene is the one the guidance image shows. Its labelled
//! masks say what is in it, so the prompt the planner reads is made from their categories
//! (`a room with 1 sofa, 2 armchair, 1 coffee table`); the vision guide then adopts every mask
//! as one of those planned objects and sizes the room from the walls it sees. The image must
//! show the floor (that is where the room and the objects stand): without it there is nothing
//! to build on, and [`photo_scene`] says so naming the file.

use std::collections::BTreeMap;

use nalgebra::Point2;
use scenethesis_imagery::{Camera, DepthMap, Intrinsics, DEFAULT_VERTICAL_FOV};
use scenethesis_scene_graph::Architecture;

use crate::camera::estimate_from_floor;
use crate::source::GivenGuidance;

/// Points within this height of y = 0 are floor.
const FLOOR_BAND_M: f64 = 0.03;

/// At least this share of the depth pixels the masks leave must be floor.
const MIN_FLOOR_SHARE: f64 = 0.02;

/// What a photo alone makes of the scene: the prompt the planner reads and what was inferred,
/// for the summary and `report.json`.
#[derive(Debug, Clone, PartialEq)]
pub struct PhotoScene {
    /// The prompt made from the masks' categories.
    pub prompt: String,
    /// What was inferred from the image, as sentences.
    pub inferred: Vec<String>,
}

/// Why a photo alone cannot make a scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PhotoError {
    /// Without labelled masks nothing says what the image shows.
    #[error(
        "{image}: no prompt and no labelled masks: give --guide-masks and --guide-labels (or a \
         prompt) so the objects of the image are known"
    )]
    NoMasks {
        /// The guidance image.
        image: String,
    },
    /// Without metric depth nothing says where the floor is.
    #[error(
        "{image}: no prompt and no depth: give --guide-depth so the visible floor can size the \
         room (or a prompt)"
    )]
    NoDepth {
        /// The guidance image.
        image: String,
    },
    /// The masks label nothing.
    #[error("{labels}: no prompt and no labelled object: the labels name nothing to build")]
    NoObjects {
        /// The labels file.
        labels: String,
    },
    /// The depth shows no floor.
    #[error(
        "{depth}: no visible floor ({reason}); a photo alone needs the floor the room stands on \
         — give a prompt to build the room offline"
    )]
    NoFloor {
        /// The depth file (or the image, when the depth came with it).
        depth: String,
        /// What was measured.
        reason: String,
    },
}

/// The scene a photo alone shows: the prompt made from `given`'s labelled masks, after
/// checking that its depth shows the floor (under its camera, else under the camera the floor
/// itself gives).
pub fn photo_scene(given: &GivenGuidance) -> Result<PhotoScene, PhotoError> {
    let files = &given.files;
    let image = files.image.display().to_string();
    let Some((masks, labels)) = &given.masks else {
        return Err(PhotoError::NoMasks { image });
    };
    let Some(depth) = &given.depth else {
        return Err(PhotoError::NoDepth { image });
    };
    let depth_file = files
        .depth
        .as_ref()
        .map_or(image, |d| d.display().to_string());
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for label in labels.values().filter(|l| masks.contains_key(&l.id)) {
        *counts.entry(label.category.as_str()).or_default() += 1;
    }
    if counts.is_empty() {
        let labels = files
            .labels
            .as_ref()
            .map_or_else(String::new, |l| l.display().to_string());
        return Err(PhotoError::NoObjects { labels });
    }
    let no_floor = |reason: String| PhotoError::NoFloor {
        depth: depth_file.clone(),
        reason,
    };
    let camera = match given.camera {
        Some(c) => c,
        None => {
            let k =
                Intrinsics::from_vertical_fov(depth.width(), depth.height(), DEFAULT_VERTICAL_FOV);
            let room = Architecture::rectangular_room(4.0, 4.0, 2.7, 0.9);
            estimate_from_floor(depth, k, &room).map_err(no_floor)?
        }
    };
    let is_masked = |u: u32, v: u32| masks.values().any(|m| m.contains(u, v));
    let share = floor_share(depth, &camera, is_masked);
    if share < MIN_FLOOR_SHARE {
        return Err(no_floor(format!(
            "{:.1} % of the unmasked depth pixels lie on y = 0 under the camera; at least {:.0} % \
             are needed",
            100.0 * share,
            100.0 * MIN_FLOOR_SHARE
        )));
    }
    let listed: Vec<String> = counts
        .iter()
        .map(|(category, n)| format!("{n} {}", category.replace('_', " ")))
        .collect();
    let prompt = format!("a room with {}", listed.join(", "));
    let inferred = vec![
        format!(
            "no prompt: the scene is the one {} shows; the plan was read from its {} labelled \
             object(s) as \"{prompt}\"",
            files.image.display(),
            counts.values().sum::<usize>()
        ),
        format!(
            "the floor is visible in {:.0} % of the depth pixels the masks leave",
            100.0 * share
        ),
    ];
    Ok(PhotoScene { prompt, inferred })
}

/// The share of `depth`'s pixels outside every mask whose point under `camera` lies on the
/// floor (within [`FLOOR_BAND_M`] of y = 0), sampled on a grid of about 160 columns.
fn floor_share(depth: &DepthMap, camera: &Camera, masked: impl Fn(u32, u32) -> bool) -> f64 {
    let stride = (depth.width().max(depth.height()) / 160).max(1) as usize;
    let (mut floor, mut all) = (0usize, 0usize);
    for v in (0..depth.height()).step_by(stride) {
        for u in (0..depth.width()).step_by(stride) {
            let Some(z) = depth.get(u, v) else { continue };
            if masked(u, v) {
                continue;
            }
            all += 1;
            let pixel = Point2::new(u as f64 + 0.5, v as f64 + 0.5);
            let p = camera.unproject(&pixel, z as f64);
            floor += (p.y.abs() < FLOOR_BAND_M) as usize;
        }
    }
    floor as f64 / all.max(1) as f64
}
