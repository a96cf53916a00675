//! Bad guidance files get one clear error naming the file and what was expected.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use nalgebra::{Point3, Vector3};
use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_vision::files::write_npy;
use scenethesis_vision_guide::{GivenGuidance, GuidanceFiles};

fn png_rgb(path: &Path, w: u32, h: u32) {
    image::RgbImage::from_pixel(w, h, image::Rgb([90, 90, 90]))
        .save(path)
        .unwrap();
}

fn png_ids(path: &Path, w: u32, h: u32, value: u16) {
    let mut img: image::ImageBuffer<image::Luma<u16>, Vec<u16>> = image::ImageBuffer::new(w, h);
    for y in h / 2..h {
        for x in w / 4..w / 2 {
            img.put_pixel(x, y, image::Luma([value]));
        }
    }
    img.save(path).unwrap();
}

fn camera_json(path: &Path, w: u32, h: u32, target_y: f64) {
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(w, h, 0.9),
        Point3::new(0.0, 1.6, 2.0),
        Point3::new(0.0, target_y, -2.0),
        Vector3::y(),
    );
    std::fs::write(path, serde_json::to_string(&camera).unwrap()).unwrap();
}

fn labels(path: &Path, category: &str) {
    std::fs::write(
        path,
        format!(r#"{{"1": {{"id": "bed_0", "category": "{category}"}}}}"#),
    )
    .unwrap();
}

fn depth(path: &Path, w: u32, h: u32, bad: Option<f32>) {
    // Nearer toward the bottom rows, as a floor seen from above (a constant depth is refused).
    let mut values: Vec<f32> = (0..w * h).map(|i| 2.0 - (i / w) as f32 * 0.01).collect();
    if let Some(b) = bad {
        values[(w + 3) as usize] = b;
    }
    std::fs::write(path, write_npy(w, h, &values)).unwrap();
}

struct Set {
    _dir: tempfile::TempDir,
    files: GuidanceFiles,
}

/// A valid set of files (64 × 48): image, masks + labels, depth and camera.
fn valid() -> Set {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| -> PathBuf { dir.path().join(n) };
    png_rgb(&p("rgb.png"), 64, 48);
    png_ids(&p("ids.png"), 64, 48, 1);
    labels(&p("labels.json"), "bed");
    depth(&p("depth.npy"), 64, 48, None);
    camera_json(&p("camera.json"), 64, 48, 0.0);
    let files = GuidanceFiles {
        image: p("rgb.png"),
        masks: Some(p("ids.png")),
        labels: Some(p("labels.json")),
        depth: Some(p("depth.npy")),
        camera: Some(p("camera.json")),
    };
    Set { _dir: dir, files }
}

fn categories() -> BTreeSet<String> {
    ["bed", "sofa"].into_iter().map(String::from).collect()
}

fn error(files: &GuidanceFiles) -> String {
    GivenGuidance::read(files, &categories())
        .expect_err("bad guidance must be refused")
        .to_string()
}

#[test]
fn a_valid_set_reads() {
    let set = valid();
    let g = GivenGuidance::read(&set.files, &categories()).unwrap();
    let (masks, labels) = g.masks.unwrap();
    assert_eq!(labels[&1].id, "bed_0");
    assert_eq!(masks["bed_0"].area(), 16 * 24);
    assert!(g.depth.is_some() && g.camera.is_some());
    let _: BTreeMap<_, _> = masks;
}

#[test]
fn an_image_of_the_wrong_size_is_refused_naming_both_files() {
    let set = valid();
    png_rgb(&set.files.image, 80, 48);
    let e = error(&set.files);
    assert!(e.contains("camera.json") && e.contains("rgb.png"), "{e}");
    assert!(e.contains("64 × 48") && e.contains("80 × 48"), "{e}");
}

#[test]
fn masks_that_do_not_match_the_image_are_refused() {
    let set = valid();
    png_ids(set.files.masks.as_ref().unwrap(), 32, 24, 1);
    let e = error(&set.files);
    assert!(e.contains("ids.png") && e.contains("32 × 24"), "{e}");
    // An instance value without a label.
    let set = valid();
    png_ids(set.files.masks.as_ref().unwrap(), 64, 48, 7);
    let e = error(&set.files);
    assert!(
        e.contains("ids.png") && e.contains("instance value 7"),
        "{e}"
    );
}

#[test]
fn nan_or_negative_depth_is_refused_naming_the_pixel() {
    for bad in [f32::NAN, -1.0] {
        let set = valid();
        depth(set.files.depth.as_ref().unwrap(), 64, 48, Some(bad));
        let e = error(&set.files);
        assert!(
            e.contains("depth.npy") && e.contains("pixel (3, 1)") && e.contains("≥ 0"),
            "{e}"
        );
    }
    let set = valid();
    depth(set.files.depth.as_ref().unwrap(), 32, 48, None);
    let e = error(&set.files);
    assert!(e.contains("depth.npy") && e.contains("32 × 48"), "{e}");
}

#[test]
fn a_camera_looking_at_the_ceiling_is_refused() {
    let set = valid();
    camera_json(set.files.camera.as_ref().unwrap(), 64, 48, 3.5);
    let e = error(&set.files);
    assert!(
        e.contains("camera.json") && e.contains("looking down at the floor"),
        "{e}"
    );
}

#[test]
fn a_label_the_library_cannot_map_is_set_aside_with_the_nearest_category() {
    let set = valid();
    labels(set.files.labels.as_ref().unwrap(), "spaceship");
    let g = GivenGuidance::read(&set.files, &categories()).unwrap();
    let (masks, kept) = g.masks.unwrap();
    assert!(kept.is_empty() && masks.is_empty(), "it guides nothing");
    assert_eq!(g.unmapped.len(), 1);
    let u = &g.unmapped[0];
    assert_eq!((u.id.as_str(), u.category.as_str()), ("bed_0", "spaceship"));
    assert!(u.nearest.is_some(), "a nearest category is offered");
    // A word the planner's nouns know is read as its category.
    labels(set.files.labels.as_ref().unwrap(), "couch");
    let g = GivenGuidance::read(&set.files, &categories()).unwrap();
    assert_eq!(g.masks.unwrap().1[&1].category, "sofa");
    assert!(g.unmapped.is_empty());
    assert!(
        g.notes[0].contains("`couch`, read as the library's `sofa`"),
        "{:?}",
        g.notes
    );
}

#[test]
fn masks_need_labels() {
    let mut set = valid();
    set.files.labels = None;
    let e = error(&set.files);
    assert!(e.contains("ids.png") && e.contains("--guide-labels"), "{e}");
}

#[test]
fn a_constant_depth_is_refused_naming_the_file() {
    let set = valid();
    std::fs::write(
        set.files.depth.as_ref().unwrap(),
        write_npy(64, 48, &vec![2.0; 64 * 48]),
    )
    .unwrap();
    let e = error(&set.files);
    assert!(
        e.contains("depth.npy") && e.contains("same depth (2 m)"),
        "{e}"
    );
}
