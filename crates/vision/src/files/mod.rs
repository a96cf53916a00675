//! Guidance on disk: the files `render DIR --guidance` writes and `--guide-*` flags read.
//!
//! | file | content |
//! |---|---|
//! | `rgb.png` | the colour image (8-bit RGB or RGBA; alpha ignored) |
//! | `depth.npy` | metric depth along the optical axis: little-endian float32 (or float64), C order, shape `(height, width)`, metres, `0` = unknown |
//! | `depth.png` | the same as a 16-bit greyscale PNG in millimetres (`0` = unknown) |
//! | `ids.png` | a 16-bit greyscale PNG of instance values, `0` = none |
//! | `labels.json` | `{"VALUE": {"id": "sofa_0", "category": "sofa"}, …}` for every value used in `ids.png` |
//! | `camera.json` | `scenethesis_imagery::Camera`: `{"intrinsics": {"width", "height", "fx", "fy", "cx", "cy"}, "position": [x, y, z], "rotation": [i, j, k, w]}` (world-from-camera; camera looks along its −Z, +Y up) |
//!
//! Every reader treats its file as hostile: sizes are bounded ([`MAX_FILE_BYTES`],
//! [`MAX_SIDE`]), values are checked, and errors name the file and what was expected.

use std::collections::BTreeMap;
use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};

use image::{ImageBuffer, Luma};
use scenethesis_imagery::{encode_png, DepthMap, Guidance, GuidanceError, RgbImage};
use serde::{Deserialize, Serialize};

/// Largest guidance file read, in bytes (512 MiB).
pub const MAX_FILE_BYTES: u64 = 512 << 20;
/// Largest image side read, in pixels.
pub const MAX_SIDE: u32 = 8192;
/// Most pixels of a guidance image (16 Mpx, e.g. 4096 × 4096 or a 12 Mpx photo); checked from
/// the PNG header or `.npy` shape before any pixel buffer is allocated.
pub const MAX_PIXELS: u64 = 1 << 24;

mod camera;
mod labels;

pub use camera::{
    check_camera, read_camera, MAX_CAMERA_JSON_BYTES, MAX_FOCAL_RATIO, MIN_FOCAL_RATIO,
    PRINCIPAL_POINT_MARGIN,
};
pub use labels::{parse_labels, read_masks, MAX_LABELS, MAX_LABELS_JSON_BYTES};

/// Why guidance files could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The file could not be opened or read.
    #[error("cannot read {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error("cannot write {path}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The file's content is not what was expected.
    #[error("{path}: {problem}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong and what was expected.
        problem: String,
    },
    /// The files disagree with each other (sizes).
    #[error("{path}: {source}")]
    Inconsistent {
        /// The file that does not fit the others.
        path: PathBuf,
        /// The mismatch.
        #[source]
        source: GuidanceError,
    },
}

fn invalid(path: &Path, problem: impl Into<String>) -> FileError {
    FileError::Invalid {
        path: path.to_path_buf(),
        problem: problem.into(),
    }
}

/// Reads at most [`MAX_FILE_BYTES`] of `path`; larger files (and endless ones such as
/// `/dev/zero`) are refused.
pub fn read_bounded(path: &Path) -> Result<Vec<u8>, FileError> {
    read_bounded_to(path, MAX_FILE_BYTES)
}

/// Reads at most `limit` bytes of `path`; larger files are refused naming the limit.
fn read_bounded_to(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    let read_err = |source| FileError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = fs::File::open(path).map_err(read_err)?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(read_err)?;
    if bytes.len() as u64 > limit {
        return Err(invalid(
            path,
            format!("larger than the {} KiB limit for this file", limit >> 10),
        ));
    }
    Ok(bytes)
}

/// Checks an image size against [`MAX_SIDE`] and [`MAX_PIXELS`].
pub fn check_image_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(format!(
            "the image is {width} × {height} pixels: expected each side 1–{MAX_SIDE} pixels"
        ));
    }
    let pixels = width as u64 * height as u64;
    if pixels > MAX_PIXELS {
        return Err(format!(
            "the image is {width} × {height} = {pixels} pixels: expected at most {MAX_PIXELS} \
             (MAX_PIXELS); downscale it and its camera's intrinsics"
        ));
    }
    Ok(())
}

/// The width and height a PNG's header states, without decoding its pixels.
pub fn png_size(path: &Path) -> Result<(u32, u32), FileError> {
    let bytes = read_bounded(path)?;
    image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png)
        .into_dimensions()
        .map_err(|e| invalid(path, format!("not a readable PNG image ({e})")))
}

/// Decodes a PNG after checking the size its header states, so a small file claiming a huge
/// image is refused before any pixel buffer is allocated.
fn decode_png(path: &Path) -> Result<image::DynamicImage, FileError> {
    let bytes = read_bounded(path)?;
    let reader =
        || image::ImageReader::with_format(std::io::Cursor::new(&bytes), image::ImageFormat::Png);
    let (w, h) = reader()
        .into_dimensions()
        .map_err(|e| invalid(path, format!("not a readable PNG image ({e})")))?;
    check_image_size(w, h).map_err(|problem| invalid(path, problem))?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    // 16-bit RGBA, the widest PNG pixel, plus the decoder's own buffers.
    limits.max_alloc = Some(MAX_PIXELS * 8 * 2);
    let mut reader = reader();
    reader.limits(limits);
    reader
        .decode()
        .map_err(|e| invalid(path, format!("not a readable PNG image ({e})")))
}

/// Reads the colour image.
pub fn read_rgb(path: &Path) -> Result<RgbImage, FileError> {
    let img = decode_png(path)?.to_rgb8();
    let (w, h) = img.dimensions();
    RgbImage::new(w, h, img.into_raw()).map_err(|source| FileError::Inconsistent {
        path: path.to_path_buf(),
        source,
    })
}

/// Reads metric depth from a `.npy` (float32/float64 metres) or a 16-bit PNG (millimetres).
/// Negative, infinite and NaN values are refused with their pixel; `0` means unknown.
pub fn read_depth(path: &Path) -> Result<DepthMap, FileError> {
    let is_png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let (w, h, values) = if is_png {
        let img = decode_png(path)?;
        let img: ImageBuffer<Luma<u16>, Vec<u16>> = match img {
            image::DynamicImage::ImageLuma16(i) => i,
            other => {
                return Err(invalid(
                    path,
                    format!(
                        "a depth PNG must be 16-bit greyscale in millimetres, found {:?}",
                        other.color()
                    ),
                ))
            }
        };
        let (w, h) = img.dimensions();
        let values = img
            .into_raw()
            .into_iter()
            .map(|mm| mm as f32 / 1000.0)
            .collect();
        (w, h, values)
    } else {
        let bytes = read_bounded(path)?;
        parse_npy(&bytes).map_err(|problem| invalid(path, problem))?
    };
    for (i, v) in values.iter().enumerate() {
        if !v.is_finite() || *v < 0.0 {
            return Err(invalid(
                path,
                format!(
                    "depth at pixel ({}, {}) is {v}: expected a finite distance ≥ 0 in metres (0 = unknown)",
                    i as u32 % w,
                    i as u32 / w
                ),
            ));
        }
    }
    DepthMap::new(w, h, values).map_err(|source| FileError::Inconsistent {
        path: path.to_path_buf(),
        source,
    })
}

/// Parses a 2-D little-endian float32/float64 C-order `.npy` array into `(width, height, values)`.
pub fn parse_npy(bytes: &[u8]) -> Result<(u32, u32, Vec<f32>), String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a NumPy .npy file (bad magic)".into());
    }
    let (header_len, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(format!("unsupported .npy version {v}")),
    };
    let header = bytes
        .get(start..start + header_len)
        .and_then(|h| std::str::from_utf8(h).ok())
        .ok_or("truncated or non-text .npy header")?;
    let field = |key: &str| -> Option<&str> {
        let at = header.find(&format!("'{key}'"))? + key.len() + 2;
        let rest = header[at..].trim_start().strip_prefix(':')?.trim_start();
        Some(rest)
    };
    let descr = field("descr").ok_or("the .npy header has no 'descr'")?;
    let elem = if descr.starts_with("'<f4'") {
        4
    } else if descr.starts_with("'<f8'") {
        8
    } else {
        return Err(format!(
            "dtype {} is not supported: expected little-endian float32 ('<f4') or float64 ('<f8')",
            descr.split(',').next().unwrap_or(descr)
        ));
    };
    if field("fortran_order").is_some_and(|f| f.starts_with("True")) {
        return Err("Fortran-order arrays are not supported: save with C order".into());
    }
    let shape = field("shape").ok_or("the .npy header has no 'shape'")?;
    let inner = shape
        .strip_prefix('(')
        .and_then(|s| s.split(')').next())
        .ok_or("malformed 'shape' in the .npy header")?;
    let dims: Vec<u64> = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<u64>()
                .map_err(|_| format!("bad dimension `{s}` in 'shape'"))
        })
        .collect::<Result<_, _>>()?;
    let [h, w] = dims[..] else {
        return Err(format!(
            "shape has {} dimensions: expected (height, width)",
            dims.len()
        ));
    };
    if w == 0 || h == 0 || w > MAX_SIDE as u64 || h > MAX_SIDE as u64 {
        return Err(format!(
            "shape ({h}, {w}): each side must be 1–{MAX_SIDE} pixels"
        ));
    }
    if w * h > MAX_PIXELS {
        return Err(format!(
            "shape ({h}, {w}) is {} pixels: expected at most {MAX_PIXELS} (MAX_PIXELS)",
            w * h
        ));
    }
    let data = &bytes[start + header_len..];
    let n = (w * h) as usize;
    if data.len() != n * elem {
        return Err(format!(
            "{} data bytes for shape ({h}, {w}): expected {}",
            data.len(),
            n * elem
        ));
    }
    let values = if elem == 4 {
        data.chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    } else {
        data.chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")) as f32)
            .collect()
    };
    Ok((w as u32, h as u32, values))
}

/// Encodes `(height, width)` float32 values as a version-1 `.npy` file.
pub fn write_npy(width: u32, height: u32, values: &[f32]) -> Vec<u8> {
    let mut header =
        format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({height}, {width}), }}");
    // Pad so that magic + version + length + header (with its newline) is a multiple of 64.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + values.len() * 4);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// The labels of an instance image, by instance value.
pub type Labels = BTreeMap<u16, Label>;

/// The labels of guidance rendered from `scene`: its objects numbered 1, 2, … in scene order
/// (what `render --guidance` writes beside the instance image).
pub fn scene_labels(scene: &scenethesis_scene_graph::Scene) -> Labels {
    scene
        .objects
        .iter()
        .zip(1u16..)
        .map(|(object, value)| {
            let label = Label {
                id: object.id.clone(),
                category: object.category.clone(),
            };
            (value, label)
        })
        .collect()
}

/// One entry of `labels.json`: the object an instance value stands for.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Label {
    /// The object's id (kept by the recovered object).
    pub id: String,
    /// Its category, e.g. `sofa`.
    pub category: String,
}

/// The paths of a guidance folder's files.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GuidancePaths {
    /// `rgb.png`.
    pub rgb: PathBuf,
    /// `depth.npy` or `depth.png`, if present.
    pub depth: Option<PathBuf>,
    /// `ids.png`.
    pub ids: PathBuf,
    /// `labels.json`.
    pub labels: PathBuf,
    /// `camera.json`.
    pub camera: PathBuf,
}

impl GuidancePaths {
    /// The conventional names inside `dir`; depth is `depth.npy`, else `depth.png`, else none.
    pub fn in_dir(dir: &Path) -> Self {
        let npy = dir.join("depth.npy");
        let png = dir.join("depth.png");
        let depth = if npy.is_file() {
            Some(npy)
        } else if png.is_file() {
            Some(png)
        } else {
            None
        };
        Self {
            rgb: dir.join("rgb.png"),
            depth,
            ids: dir.join("ids.png"),
            labels: dir.join("labels.json"),
            camera: dir.join("camera.json"),
        }
    }
}

/// Reads a whole guidance set and checks that every image has the camera's size.
pub fn read_guidance(paths: &GuidancePaths) -> Result<(Guidance, BTreeMap<u16, Label>), FileError> {
    let camera = read_camera(&paths.camera)?;
    let image = read_rgb(&paths.rgb)?;
    let depth = paths.depth.as_deref().map(read_depth).transpose()?;
    let (masks, labels) = read_masks(&paths.ids, &paths.labels)?;
    let (cw, ch) = (camera.intrinsics.width, camera.intrinsics.height);
    let check = |path: &Path, w: u32, h: u32| {
        if (w, h) == (cw, ch) {
            Ok(())
        } else {
            Err(invalid(
                path,
                format!(
                    "is {w} × {h} pixels but {} says {cw} × {ch}",
                    paths.camera.display()
                ),
            ))
        }
    };
    check(&paths.rgb, image.width(), image.height())?;
    if let (Some(d), Some(p)) = (&depth, &paths.depth) {
        check(p, d.width(), d.height())?;
    }
    let (iw, ih) = match masks.values().next() {
        Some(m) => (m.width(), m.height()),
        None => png_size(&paths.ids)?,
    };
    check(&paths.ids, iw, ih)?;
    let guidance =
        Guidance::new(camera, image, depth, masks).map_err(|source| FileError::Inconsistent {
            path: paths.rgb.clone(),
            source,
        })?;
    Ok((guidance, labels))
}

/// Encodes a guidance set as the files of [`GuidancePaths::in_dir`] (depth as `depth.npy`),
/// returned as `(file name, bytes)` pairs for the caller to write atomically. Instance values
/// follow `labels`' order; masks without a label are left out.
pub fn encode_guidance(
    guidance: &Guidance,
    labels: &BTreeMap<u16, Label>,
) -> Result<Vec<(&'static str, Vec<u8>)>, FileError> {
    let (w, h) = (
        guidance.camera.intrinsics.width,
        guidance.camera.intrinsics.height,
    );
    let png_err = |name: &str, e: image::ImageError| {
        invalid(Path::new(name), format!("PNG encoding failed: {e}"))
    };
    let mut out = Vec::new();
    let rgb = image::RgbImage::from_raw(w, h, guidance.image.as_bytes().to_vec())
        .ok_or_else(|| invalid(Path::new("rgb.png"), "image size disagrees with the camera"))?;
    out.push((
        "rgb.png",
        encode_png(&rgb).map_err(|e| png_err("rgb.png", e))?,
    ));
    if let Some(d) = &guidance.depth {
        let values: Vec<f32> = d
            .values()
            .iter()
            .map(|v| if v.is_finite() { *v } else { 0.0 })
            .collect();
        out.push(("depth.npy", write_npy(w, h, &values)));
    }
    let mut ids: ImageBuffer<Luma<u16>, Vec<u16>> = ImageBuffer::new(w, h);
    for (value, label) in labels {
        if let Some(mask) = guidance.masks.get(&label.id) {
            for (x, y) in mask.pixels() {
                ids.put_pixel(x, y, Luma([*value]));
            }
        }
    }
    out.push((
        "ids.png",
        encode_png(&ids).map_err(|e| png_err("ids.png", e))?,
    ));
    let labels_json: BTreeMap<String, &Label> =
        labels.iter().map(|(k, v)| (k.to_string(), v)).collect();
    let mut text = serde_json::to_string_pretty(&labels_json).expect("labels serialize");
    text.push('\n');
    out.push(("labels.json", text.into_bytes()));
    let mut cam = serde_json::to_string_pretty(&guidance.camera).expect("camera serializes");
    cam.push('\n');
    out.push(("camera.json", cam.into_bytes()));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn npy_round_trip_and_refusals() {
        let bytes = write_npy(3, 2, &[0.0, 1.0, 2.0, 3.0, 4.0, 5.5]);
        assert_eq!(bytes.len() % 4, 0);
        let (w, h, v) = parse_npy(&bytes).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(v[5], 5.5);
        assert!(parse_npy(&bytes[..bytes.len() - 1])
            .unwrap_err()
            .contains("data bytes"));
        assert!(parse_npy(b"hello world").unwrap_err().contains("magic"));
        let mut f8 = bytes.clone();
        let at = f8.windows(3).position(|w| w == b"<f4").unwrap();
        f8[at + 2] = b'2';
        assert!(parse_npy(&f8).unwrap_err().contains("'<f2'"));
    }
}
