//! Guidance files: a written set reads back equal; bad files are refused naming the file.

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::{Point3, Vector3};
use scenethesis_imagery::{Camera, DepthMap, Guidance, Intrinsics, Mask, RgbImage};
use scenethesis_vision::files::{encode_guidance, read_guidance, write_npy, GuidancePaths, Label};

fn sample() -> (Guidance, BTreeMap<u16, Label>) {
    let (w, h) = (40, 30);
    let k = Intrinsics::from_vertical_fov(w, h, 1.0);
    let camera = Camera::look_at(
        k,
        Point3::new(0.0, 1.5, 2.0),
        Point3::origin(),
        Vector3::y(),
    );
    let image = RgbImage::new(w, h, (0..w * h * 3).map(|i| (i % 251) as u8).collect()).unwrap();
    let depth = DepthMap::from_fn(w, h, |u, v| {
        if u == 0 {
            0.0
        } else {
            1.0 + (u + v) as f32 * 0.01
        }
    });
    let mut a = Mask::new(w, h);
    let mut b = Mask::new(w, h);
    for v in 5..10 {
        for u in 5..12 {
            a.set(u, v, true);
            b.set(u + 20, v + 10, true);
        }
    }
    let masks = BTreeMap::from([("sofa_0".to_string(), a), ("lamp_0".to_string(), b)]);
    let labels = BTreeMap::from([
        (
            1,
            Label {
                id: "sofa_0".into(),
                category: "sofa".into(),
            },
        ),
        (
            7,
            Label {
                id: "lamp_0".into(),
                category: "floor_lamp".into(),
            },
        ),
    ]);
    (
        Guidance::new(camera, image, Some(depth), masks).unwrap(),
        labels,
    )
}

fn write_all(dir: &Path, files: &[(&str, Vec<u8>)]) {
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

#[test]
fn written_guidance_reads_back_equal() {
    let (guidance, labels) = sample();
    let dir = tempfile::tempdir().unwrap();
    write_all(dir.path(), &encode_guidance(&guidance, &labels).unwrap());
    let (read, read_labels) = read_guidance(&GuidancePaths::in_dir(dir.path())).unwrap();
    assert_eq!(read_labels, labels);
    assert_eq!(read.image, guidance.image);
    assert_eq!(read.masks, guidance.masks);
    assert_eq!(read.depth, guidance.depth);
    assert_eq!(read.camera.intrinsics, guidance.camera.intrinsics);
    assert!((read.camera.position - guidance.camera.position).norm() < 1e-12);
}

#[test]
fn bad_files_name_the_file_and_the_problem() {
    let (guidance, labels) = sample();
    let files = encode_guidance(&guidance, &labels).unwrap();
    let err = |mutate: &dyn Fn(&Path)| {
        let dir = tempfile::tempdir().unwrap();
        write_all(dir.path(), &files);
        mutate(dir.path());
        read_guidance(&GuidancePaths::in_dir(dir.path()))
            .unwrap_err()
            .to_string()
    };
    // NaN and negative depth.
    let e = err(&|d| {
        std::fs::write(
            d.join("depth.npy"),
            write_npy(40, 30, &vec![f32::NAN; 1200]),
        )
        .unwrap()
    });
    assert!(e.contains("depth.npy") && e.contains("NaN"), "{e}");
    let e = err(&|d| {
        std::fs::write(d.join("depth.npy"), write_npy(40, 30, &vec![-1.0; 1200])).unwrap()
    });
    assert!(e.contains("depth.npy") && e.contains("-1"), "{e}");
    // Depth of the wrong size.
    let e =
        err(&|d| std::fs::write(d.join("depth.npy"), write_npy(20, 30, &vec![1.0; 600])).unwrap());
    assert!(e.contains("depth.npy") && e.contains("20 × 30"), "{e}");
    // An image of the wrong size.
    let e = err(&|d| {
        image::RgbImage::new(41, 30)
            .save(d.join("rgb.png"))
            .unwrap();
    });
    assert!(e.contains("rgb.png") && e.contains("41 × 30"), "{e}");
    // An instance value without a label.
    let e = err(&|d| {
        std::fs::write(
            d.join("labels.json"),
            r#"{"1": {"id": "sofa_0", "category": "sofa"}}"#,
        )
        .unwrap()
    });
    assert!(e.contains("ids.png") && e.contains("value 7"), "{e}");
    // Labels that are not the documented shape.
    let e = err(&|d| std::fs::write(d.join("labels.json"), r#"{"1": "sofa"}"#).unwrap());
    assert!(e.contains("labels.json") && e.contains("\"id\""), "{e}");
    // A camera with a zero focal length; a truncated one.
    let e = err(&|d| {
        let text = std::fs::read_to_string(d.join("camera.json")).unwrap();
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v["intrinsics"]["fx"] = 0.0.into();
        std::fs::write(d.join("camera.json"), v.to_string()).unwrap();
    });
    assert!(e.contains("camera.json") && e.contains("focal"), "{e}");
    let e = err(&|d| std::fs::write(d.join("camera.json"), "{\"intrinsics\": {").unwrap());
    assert!(e.contains("camera.json"), "{e}");
    // A missing file.
    let e = err(&|d| std::fs::remove_file(d.join("ids.png")).unwrap());
    assert!(e.contains("cannot read") && e.contains("ids.png"), "{e}");
}
