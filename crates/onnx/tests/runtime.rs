//! The providers run through the real ONNX Runtime on the tiny models in `fixtures/onnx`
//! (written by `fixtures/onnx/make_models.py`), whose outputs are known functions of their
//! inputs, so the pre- and post-processing are checked numerically.
//!
//! Needs the `runtime` feature and `ORT_DYLIB_PATH` naming an ONNX Runtime library (`.ci/run`
//! installs the `onnxruntime` wheel and sets it); without the variable every test fails saying
//! how to get the library.
#![cfg(feature = "runtime")]

use std::path::PathBuf;

use image::{Rgb, RgbImage};
use scenethesis_imagery::Intrinsics;
use scenethesis_models::{BoxPrompt, DepthEstimator, ImageData, ProviderErrorKind, Segmenter};
use scenethesis_onnx::{
    DepthConfig, DepthOutput, Normalisation, OnnxDepth, OnnxError, OnnxSegmenter, Runtime,
    SegmenterConfig,
};

fn runtime() -> Runtime {
    Runtime::from_env()
        .unwrap_or_else(|e| panic!("these tests run models through ONNX Runtime: {e}"))
}

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/onnx")
        .join(name)
}

fn png(img: &RgbImage) -> ImageData {
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    ImageData::from_bytes(out.into_inner(), "test image").unwrap()
}

/// The tiny depth models' function of one uniform colour: 1.5 x channel mean + 4.
fn depth_of(colour: [u8; 3]) -> f32 {
    let n = Normalisation::IMAGENET;
    let mean = (0..3).map(|c| n.apply(c, colour[c])).sum::<f32>() / 3.0;
    1.5 * mean + 4.0
}

fn assert_close(got: f32, want: f32, what: &str) {
    assert!((got - want).abs() < 1e-4, "{what}: got {got}, want {want}");
}

#[test]
fn depth_on_a_dynamic_model_comes_back_at_image_size() {
    let rt = runtime();
    let config = DepthConfig {
        input_size: 28,
        output_kind: DepthOutput::Metric { scale: 2.0 },
        ..DepthConfig::default()
    };
    let depth = OnnxDepth::new(&rt, fixture("depth_dynamic.onnx"), config).unwrap();
    assert_eq!(depth.name(), "onnx/depth_dynamic");
    // 40 x 30, left half one colour, right half another: the model sees 42 x 28.
    assert_eq!(depth.input_size_for(40, 30), (42, 28));
    let (a, b) = ([200, 30, 90], [10, 220, 140]);
    let img = RgbImage::from_fn(40, 30, |x, _| Rgb(if x < 20 { a } else { b }));
    let k = Intrinsics {
        width: 40,
        height: 30,
        fx: 50.0,
        fy: 51.0,
        cx: 20.0,
        cy: 15.0,
    };
    let map = depth.estimate(&png(&img), Some(k)).unwrap();
    assert_eq!(
        (
            map.depth.width(),
            map.depth.height(),
            map.depth.values().len()
        ),
        (40, 30, 1200)
    );
    assert_eq!(map.intrinsics, k);
    for y in 0..30 {
        for x in (0..=16).chain(23..40) {
            let want = 2.0 * depth_of(if x < 20 { a } else { b });
            assert_close(
                map.depth.get(x, y).unwrap(),
                want,
                &format!("depth at ({x}, {y})"),
            );
        }
        // Across the boundary the depth moves monotonically from one side to the other.
        let row: Vec<f32> = (16..=23).map(|x| map.depth.get(x, y).unwrap()).collect();
        let rising = depth_of(b) > depth_of(a);
        assert!(
            row.windows(2)
                .all(|w| (w[1] >= w[0] - 1e-5) == rising || (w[1] - w[0]).abs() < 1e-5),
            "{row:?}"
        );
    }
    // Without intrinsics the assumed 60 degree field of view is used.
    let map = depth.estimate(&png(&img), None).unwrap();
    let f = 20.0 / (30f64.to_radians()).tan();
    assert!((map.intrinsics.fx - f).abs() < 1e-3, "{:?}", map.intrinsics);
}

#[test]
fn depth_on_a_static_model_uses_its_size_and_keeps_rows_and_columns() {
    let rt = runtime();
    let config = DepthConfig {
        output_kind: DepthOutput::RelativeInverse { scale: 10.0 },
        ..DepthConfig::default()
    };
    let depth = OnnxDepth::new(&rt, fixture("depth_static.onnx"), config).unwrap();
    // The model's input is [1, 3, 28, 42] whatever the image.
    assert_eq!(depth.input_size_for(60, 20), (42, 28));
    assert_eq!(depth.input_size_for(7, 900), (42, 28));
    // 60 x 20, top half one colour, bottom half another (a transposed tensor would mix them).
    let (a, b) = ([250, 250, 250], [0, 0, 60]);
    let img = RgbImage::from_fn(60, 20, |_, y| Rgb(if y < 10 { a } else { b }));
    let map = depth.estimate(&png(&img), None).unwrap();
    assert_eq!((map.depth.width(), map.depth.height()), (60, 20));
    for x in 0..60 {
        for y in (0..=6).chain(13..20) {
            let want = 10.0 / depth_of(if y < 10 { a } else { b });
            assert_close(
                map.depth.get(x, y).unwrap(),
                want,
                &format!("depth at ({x}, {y})"),
            );
        }
    }
}

/// Pixels whose centre lies inside `bbox` (normalised) by more than `margin` pixels, and those
/// outside by more than `margin`.
fn inside(bbox: [f32; 4], w: u32, h: u32, x: u32, y: u32, margin: f32) -> Option<bool> {
    let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
    let (x0, y0, x1, y1) = (
        bbox[0] * w as f32,
        bbox[1] * h as f32,
        bbox[2] * w as f32,
        bbox[3] * h as f32,
    );
    let d = (px - x0).min(x1 - px).min(py - y0).min(y1 - py);
    if d > margin {
        Some(true)
    } else if d < -margin {
        Some(false)
    } else {
        None
    }
}

fn check_segmentation(width: u32, height: u32, boxes: &[[f32; 4]]) {
    let rt = runtime();
    let seg = OnnxSegmenter::new(
        &rt,
        fixture("sam_encoder.onnx"),
        fixture("sam_decoder.onnx"),
        SegmenterConfig::default(),
    )
    .unwrap();
    assert_eq!(seg.input_size(), 1024);
    assert_eq!(seg.name(), "onnx/sam_encoder+sam_decoder");
    let colour = [180u8, 120, 40];
    let img = RgbImage::from_pixel(width, height, Rgb(colour));
    let prompts: Vec<BoxPrompt> = boxes
        .iter()
        .enumerate()
        .map(|(i, b)| BoxPrompt {
            label: format!("object_{i}"),
            bbox: *b,
        })
        .collect();
    let masks = seg.segment(&png(&img), &prompts).unwrap();
    assert_eq!(masks.len(), boxes.len());

    // The decoder's IoU is 0.6 + 0.1 x the mean embedding, i.e. of the normalised image
    // zero-padded to the 1024 x 1024 frame.
    let scale = 1024.0 / width.max(height) as f64;
    let (rw, rh) = (
        (width as f64 * scale + 0.5).floor(),
        (height as f64 * scale + 0.5).floor(),
    );
    let n = Normalisation::IMAGENET;
    let channel_mean = (0..3)
        .map(|c| f64::from(n.apply(c, colour[c])))
        .sum::<f64>()
        / 3.0;
    let want_score = 0.6 + 0.1 * channel_mean * rw * rh / (1024.0 * 1024.0);

    for (mask, (prompt, bbox)) in masks.iter().zip(prompts.iter().zip(boxes)) {
        assert_eq!(mask.label, prompt.label);
        assert_eq!((mask.mask.width(), mask.mask.height()), (width, height));
        assert_close(mask.score, want_score as f32, "score");
        let mut unsure = 0;
        for y in 0..height {
            for x in 0..width {
                let got = mask.mask.contains(x, y);
                match inside(*bbox, width, height, x, y, 0.0) {
                    // Away from the corners the logits are linear across the edges, so the
                    // mask edge is exact; within a pixel of a corner it may cut the corner.
                    Some(want) if inside(*bbox, width, height, x, y, 1.0).is_some() || !want => {
                        let near_corner = [bbox[0], bbox[2]]
                            .iter()
                            .any(|bx| (x as f32 + 0.5 - bx * width as f32).abs() < 1.5)
                            && [bbox[1], bbox[3]]
                                .iter()
                                .any(|by| (y as f32 + 0.5 - by * height as f32).abs() < 1.5);
                        if near_corner {
                            unsure += usize::from(got != want);
                        } else {
                            assert_eq!(
                                got, want,
                                "{} pixel ({x}, {y}) of a {width} x {height} image",
                                prompt.label
                            );
                        }
                    }
                    _ => unsure += usize::from(!got),
                }
            }
        }
        assert!(
            unsure <= 8,
            "{}: {unsure} pixels off near the corners",
            prompt.label
        );
    }
}

#[test]
fn segmenter_masks_land_on_their_boxes_in_a_landscape_image() {
    check_segmentation(200, 120, &[[0.1, 0.2, 0.6, 0.9], [0.55, 0.05, 0.95, 0.5]]);
}

#[test]
fn segmenter_masks_land_on_their_boxes_in_a_portrait_image() {
    // The frame is padded on the right; a box reaching the right edge must stop there.
    check_segmentation(90, 160, &[[0.5, 0.25, 1.0, 0.75], [0.0, 0.6, 0.3, 0.95]]);
}

#[test]
fn segmenter_rejects_bad_boxes_naming_them_and_needs_no_model_run_for_none() {
    let rt = runtime();
    let seg = OnnxSegmenter::new(
        &rt,
        fixture("sam_encoder.onnx"),
        fixture("sam_decoder.onnx"),
        SegmenterConfig::default(),
    )
    .unwrap();
    let img = png(&RgbImage::new(8, 8));
    assert!(seg.segment(&img, &[]).unwrap().is_empty());
    let err = seg
        .segment(
            &img,
            &[BoxPrompt {
                label: "lamp_2".into(),
                bbox: [0.6, 0.1, 0.2, 0.5],
            }],
        )
        .unwrap_err();
    assert!(
        matches!(err.kind, ProviderErrorKind::InvalidRequest { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("lamp_2"), "{err}");
    assert!(err.to_string().starts_with("onnxruntime (model `"), "{err}");
}

#[test]
fn wrong_models_and_files_are_named_in_errors() {
    let rt = runtime();
    // A decoder without the SAM decoder inputs.
    let err = OnnxSegmenter::new(
        &rt,
        fixture("sam_encoder.onnx"),
        fixture("depth_dynamic.onnx"),
        SegmenterConfig::default(),
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, OnnxError::Signature { .. }), "{text}");
    assert!(
        text.contains("depth_dynamic.onnx") && text.contains("no input `image_embeddings`"),
        "{text}"
    );
    assert!(text.contains("`image` float32[1, 3, ?, ?]"), "{text}");

    // A depth model must have one image input.
    let err = OnnxDepth::new(&rt, fixture("sam_decoder.onnx"), DepthConfig::default()).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("sam_decoder.onnx") && text.contains("expected one input"),
        "{text}"
    );

    // A named input that is not there.
    let config = DepthConfig {
        input: Some("pixel_values".into()),
        ..DepthConfig::default()
    };
    let err = OnnxDepth::new(&rt, fixture("depth_dynamic.onnx"), config).unwrap_err();
    assert!(err.to_string().contains("no input `pixel_values`"), "{err}");

    // A missing model file.
    let err = OnnxDepth::new(&rt, fixture("missing.onnx"), DepthConfig::default()).unwrap_err();
    assert!(
        matches!(err, OnnxError::Model { .. }) && err.to_string().contains("missing.onnx"),
        "{err}"
    );

    // A corrupt image.
    let depth = OnnxDepth::new(&rt, fixture("depth_dynamic.onnx"), DepthConfig::default()).unwrap();
    let mut bytes = png(&RgbImage::new(4, 4)).bytes;
    bytes.truncate(20);
    let broken = ImageData::from_bytes(bytes, "broken").unwrap();
    let err = depth.estimate(&broken, None).unwrap_err();
    assert!(
        err.to_string().contains("depth_dynamic.onnx") && err.to_string().contains("decode"),
        "{err}"
    );
}

#[test]
fn library_errors_name_the_path_and_how_to_get_the_library() {
    let loaded = runtime();
    let err = Runtime::load("/nonexistent/libonnxruntime.so.1").unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("/nonexistent/libonnxruntime.so.1") && text.contains("no such file"),
        "{text}"
    );
    assert!(text.contains("pip install onnxruntime"), "{text}");
    // Another file than the loaded library: a process loads ONNX Runtime once.
    let other = fixture("depth_static.onnx");
    let err = Runtime::load(&other).unwrap_err();
    assert!(err.to_string().contains("depth_static.onnx"), "{err}");
    // The same library again is the same runtime.
    let again = Runtime::load(loaded.library()).unwrap();
    assert_eq!(again.library(), loaded.library());
}

mod dense_matcher {
    use nalgebra::{Point3, Vector3};
    use scenethesis_correspondence::{lift, rasterize, Matcher, TargetRegion, Window};
    use scenethesis_imagery::{Camera, DepthMap, Intrinsics, Mask, RgbImage};
    use scenethesis_onnx::matcher::{crop_for, matcher_inputs};
    use scenethesis_onnx::{MatcherConfig, OnnxError, OnnxMatcher};
    use scenethesis_scene_graph::{Material, Mesh, Pose};

    use super::{fixture, runtime};

    fn camera() -> Camera {
        Camera::look_at(
            Intrinsics::from_vertical_fov(160, 120, 1.0),
            Point3::new(1.5, 2.0, 4.5),
            Point3::new(0.0, 0.4, 0.0),
            Vector3::y(),
        )
    }

    /// Intensity-weighted centroid of a row-major plane (pixel k's centre at k + 0.5).
    fn centroid(plane: &[f32], width: u32) -> [f64; 2] {
        let (mut m, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for (i, v) in plane.iter().enumerate() {
            let (x, y) = (
                (i as u32 % width) as f64 + 0.5,
                (i as u32 / width) as f64 + 0.5,
            );
            m += *v as f64;
            sx += *v as f64 * x;
            sy += *v as f64 * y;
        }
        [sx / m, sy / m]
    }

    /// The tiny matcher (fixtures/onnx/matcher_centroid.onnx) pairs points around the two
    /// inputs' intensity centroids, so through the real runtime every kept pair must carry the
    /// shift between the rendered asset and its object as the Rust pre-processing drew them,
    /// land on the asset and on the mask, and lift to correspondences with target points.
    #[test]
    fn dense_matcher_pairs_carry_the_shift_between_render_and_guidance() {
        let rt = runtime();
        let config = MatcherConfig {
            input_size: 96,
            ..MatcherConfig::default()
        };
        let matcher = OnnxMatcher::new(&rt, fixture("matcher_centroid.onnx"), config).unwrap();
        assert_eq!(matcher.name(), "onnx/matcher_centroid");
        let cam = camera();
        let grey = Material::new("grey", [0.5; 3], 0.8);
        let mesh = Mesh::cuboid("box", grey, [-0.4, 0.0, -0.3], [0.4, 0.8, 0.3]);
        let truth = Pose::new(1.0, 0.3, Vector3::new(0.1, 0.0, -0.2));
        let start = Pose::new(1.0, 0.3, Vector3::new(0.5, 0.0, -0.2));
        let seen = rasterize(&mesh, &truth, &cam, Window::full(&cam));
        let (w, h) = (160, 120);
        let mut mask = Mask::new(w, h);
        let mut pixels = vec![40u8; (w * h * 3) as usize];
        for y in 0..h {
            for x in 0..w {
                if seen.depth.get(x, y).is_some() {
                    mask.set(x, y, true);
                    let i = ((y * w + x) * 3) as usize;
                    pixels[i..i + 3].copy_from_slice(&[180, 170, 160]);
                }
            }
        }
        let image = RgbImage::new(w, h, pixels).unwrap();
        let depth = DepthMap::from_fn(w, h, |x, y| seen.depth.get(x, y).unwrap_or(6.0));
        let target = TargetRegion {
            camera: &cam,
            mask: &mask,
            depth: Some(&depth),
            image: Some(&image),
        };
        let window = rasterize(&mesh, &start, &cam, Window::full(&cam));
        let bbox = scenethesis_correspondence::projected_bbox(&mesh, &start, &cam).unwrap();
        let view = rasterize(&mesh, &start, &cam, Window::around(bbox, 2, w, h).unwrap());
        assert!(window.coverage() == view.coverage() && view.coverage() > 300);

        let matches = matcher.match_view(&view, &target);
        // Of the model's 25 pairs, the 16 of the outer ring are below the confidence floor.
        assert!(
            (5..=9).contains(&matches.len()),
            "{} matches: {matches:?}",
            matches.len()
        );
        assert!(matches
            .windows(2)
            .all(|p| p[0].confidence >= p[1].confidence));
        assert_eq!(matches[0].confidence, 1.0);

        let crop = crop_for(&view, &target, MatcherConfig::default().margin).unwrap();
        let (rendered, guidance) = matcher_inputs(&view, &target, crop).unwrap();
        let (c0, c1) = (
            centroid(&rendered, crop.width),
            centroid(&guidance, crop.width),
        );
        let shift = [c1[0] - c0[0], c1[1] - c0[1]];
        assert!(shift[0].abs() > 5.0, "the start is off by {shift:?} px");
        for m in &matches {
            let (gx, gy) = view.to_guidance(m.rendered[0], m.rendered[1]);
            let got = [
                m.target.x - (gx as f64 + 0.5),
                m.target.y - (gy as f64 + 0.5),
            ];
            // Half a pixel from flooring the rendered point, a little from resizing.
            assert!(
                (got[0] - shift[0]).abs() < 1.2 && (got[1] - shift[1]).abs() < 1.2,
                "pair {m:?} moves {got:?}, the inputs' centroids {shift:?}"
            );
            assert!(view.depth.get(m.rendered[0], m.rendered[1]).is_some());
            assert!(mask.contains(m.target.x as u32, m.target.y as u32));
        }
        let pairs = lift(&matches, &view, &target);
        assert_eq!(pairs.len(), matches.len());
        assert!(pairs.iter().all(|p| p.target_point.is_some()));

        // Without the guidance image there is nothing to compare: no matches.
        let blind = TargetRegion {
            image: None,
            ..target
        };
        assert!(matcher.match_view(&view, &blind).is_empty());
    }

    #[test]
    fn a_model_without_the_matcher_signature_is_refused_by_name() {
        let rt = runtime();
        let err = OnnxMatcher::new(&rt, fixture("depth_dynamic.onnx"), MatcherConfig::default())
            .unwrap_err();
        assert!(matches!(err, OnnxError::Signature { .. }), "{err}");
        let text = err.to_string();
        assert!(
            text.contains("depth_dynamic.onnx") && text.contains("no input `image0`"),
            "{text}"
        );
    }
}
