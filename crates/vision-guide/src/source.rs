//! Where the guidance image comes from: files the user gives ([`GivenGuidance`], read and
//! checked up front), or an image model's edit of our render of the plan's empty room
//! ([`scenethesis_render_api::SceneRenderer`] + [`scenethesis_models::ImageGenerator`]), whose
//! camera is then known.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use scenethesis_agents::{Knowledge, UnmappedLabel};
use scenethesis_imagery::{Camera, DepthMap, Mask, RgbImage};
use scenethesis_vision::files::{self, FileError, Labels};

/// Why given guidance files cannot be used. Every variant names the file at fault and what was
/// expected.
#[derive(Debug, thiserror::Error)]
pub enum GuidanceFileError {
    /// A file could not be read, or its content is invalid.
    #[error(transparent)]
    File(#[from] FileError),
    /// Two files disagree on the image size.
    #[error("{path}: is {width} × {height} pixels but {other} is {other_width} × {other_height}; every guidance image must have the same size")]
    SizeMismatch {
        /// The file that does not fit.
        path: PathBuf,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
        /// The file it was compared with.
        other: PathBuf,
        /// That file's width.
        other_width: u32,
        /// That file's height.
        other_height: u32,
    },
    /// The camera cannot see the floor (it looks level or up, or is below the floor).
    #[error("{path}: {problem}")]
    Camera {
        /// The camera file.
        path: PathBuf,
        /// What is wrong and what was expected.
        problem: String,
    },
    /// Masks were given without labels or the other way round.
    #[error("{0}")]
    Incomplete(String),
}

/// Paths of the guidance files a user gives (`--guide-image`, `--guide-masks`,
/// `--guide-labels`, `--guide-depth`, `--camera`). Only the image is required.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct GuidanceFiles {
    /// The colour image (PNG).
    pub image: PathBuf,
    /// The 16-bit instance PNG (0 = none); needs `labels`.
    pub masks: Option<PathBuf>,
    /// `labels.json` for `masks`.
    pub labels: Option<PathBuf>,
    /// Metric depth: `.npy` float32 metres, or a 16-bit PNG in millimetres.
    pub depth: Option<PathBuf>,
    /// `camera.json` (the serde form of `scenethesis_imagery::Camera`).
    pub camera: Option<PathBuf>,
}

/// Guidance read from files and checked: sizes agree, depth is finite and non-negative, the
/// camera looks down at the floor. Every label names a category of the asset library: its own,
/// or the one its words name (`couch` → `sofa`); a label the library cannot map is taken out
/// (with its mask) and listed in [`GivenGuidance::unmapped`] with the nearest category.
#[derive(Debug, Clone, PartialEq)]
pub struct GivenGuidance {
    /// The files it was read from (named in later errors and notes).
    pub files: GuidanceFiles,
    /// The colour image.
    pub image: RgbImage,
    /// The PNG bytes of the image as read (sent to models unchanged).
    pub image_png: Vec<u8>,
    /// Metric depth, when given.
    pub depth: Option<DepthMap>,
    /// The camera, when given.
    pub camera: Option<Camera>,
    /// Masks by label id and the labels (categories mapped onto the library's), when given.
    pub masks: Option<(BTreeMap<String, Mask>, Labels)>,
    /// Labels whose category the library cannot map, with the nearest category it has.
    pub unmapped: Vec<UnmappedLabel>,
    /// Labels whose category was read as another (`labels.json: label 3 (`couch_0`) names
    /// `couch`, read as `sofa``).
    pub notes: Vec<String>,
}

impl GivenGuidance {
    /// Reads and checks `files`. `categories` are the asset library's categories; a label
    /// naming another category is read as the library category its words name, else set aside
    /// in [`GivenGuidance::unmapped`].
    pub fn read(
        files: &GuidanceFiles,
        categories: &BTreeSet<String>,
    ) -> Result<Self, GuidanceFileError> {
        let image_png = files::read_bounded(&files.image)?;
        let image = files::read_rgb(&files.image)?;
        let size = (image.width(), image.height());
        let same = |path: &Path, w: u32, h: u32| -> Result<(), GuidanceFileError> {
            if (w, h) == size {
                Ok(())
            } else {
                Err(GuidanceFileError::SizeMismatch {
                    path: path.to_path_buf(),
                    width: w,
                    height: h,
                    other: files.image.clone(),
                    other_width: size.0,
                    other_height: size.1,
                })
            }
        };
        let camera = match &files.camera {
            Some(path) => {
                let camera = files::read_camera(path)?;
                same(path, camera.intrinsics.width, camera.intrinsics.height)?;
                scenethesis_vision::metrology::check_camera(&camera).map_err(|e| {
                    GuidanceFileError::Camera {
                        path: path.clone(),
                        problem: e.to_string(),
                    }
                })?;
                Some(camera)
            }
            None => None,
        };
        let depth = match &files.depth {
            Some(path) => {
                let depth = files::read_depth(path)?;
                same(path, depth.width(), depth.height())?;
                check_depth_varies(&depth).map_err(|problem| FileError::Invalid {
                    path: path.clone(),
                    problem,
                })?;
                Some(depth)
            }
            None => None,
        };
        let mut unmapped = Vec::new();
        let mut notes = Vec::new();
        let masks = match (&files.masks, &files.labels) {
            (Some(ids), Some(labels_path)) => {
                let (masks, labels) = files::read_masks(ids, labels_path)?;
                if let Some(m) = masks.values().next() {
                    same(ids, m.width(), m.height())?;
                } else {
                    // No label: still check the instance image's size.
                    let (w, h) = files::png_size(ids)?;
                    same(ids, w, h)?;
                }
                let (masks, (labels, set_aside, read_as)) =
                    map_categories(masks, labels, categories, labels_path);
                unmapped = set_aside;
                notes = read_as;
                Some((masks, labels))
            }
            (Some(ids), None) => {
                return Err(GuidanceFileError::Incomplete(format!(
                    "{}: an instance image needs its labels (--guide-labels labels.json)",
                    ids.display()
                )))
            }
            (None, Some(labels)) => {
                return Err(GuidanceFileError::Incomplete(format!(
                    "{}: labels need their instance image (--guide-masks ids.png)",
                    labels.display()
                )))
            }
            (None, None) => None,
        };
        Ok(Self {
            files: files.clone(),
            image,
            image_png,
            depth,
            camera,
            masks,
            unmapped,
            notes,
        })
    }
}

/// Labels (with their masks) whose categories are the library's, those the library cannot map,
/// and a note per category read as another.
type MappedLabels = (Labels, Vec<UnmappedLabel>, Vec<String>);

/// Reads every label's category as a library category ([`library_category`]); labels the
/// library cannot map leave with their masks.
fn map_categories(
    mut masks: BTreeMap<String, Mask>,
    labels: Labels,
    categories: &BTreeSet<String>,
    path: &Path,
) -> (BTreeMap<String, Mask>, MappedLabels) {
    let mut kept = Labels::new();
    let mut unmapped = Vec::new();
    let mut notes = Vec::new();
    for (value, mut label) in labels {
        match library_category(&label.category, categories) {
            Ok(category) => {
                if category != label.category {
                    notes.push(format!(
                        "{}: label {value} (`{}`) names `{}`, read as the library's `{category}`",
                        path.display(),
                        label.id,
                        label.category
                    ));
                    label.category = category;
                }
                kept.insert(value, label);
            }
            Err(nearest) => {
                masks.remove(&label.id);
                unmapped.push(UnmappedLabel {
                    id: label.id,
                    category: label.category,
                    nearest,
                });
            }
        }
    }
    (masks, (kept, unmapped, notes))
}

/// The library category a label's `category` stands for: itself when the library has it, else
/// the category its words name by the planner's nouns (`couch` → `sofa`, `Coffee Tables` →
/// `coffee_table`). `Err` holds the nearest library category: the one whose naming words the
/// label contains the most of (`pharmacy shelf` → `shelf`), else the closest in spelling.
pub fn library_category(
    category: &str,
    categories: &BTreeSet<String>,
) -> Result<String, Option<String>> {
    if categories.contains(category) {
        return Ok(category.to_owned());
    }
    let knowledge = Knowledge::builtin();
    if let Some(c) = knowledge
        .category_of_phrase(category)
        .filter(|c| categories.contains(*c))
    {
        return Ok(c.to_owned());
    }
    let rows = knowledge
        .category_phrases()
        .iter()
        .filter(|(_, c)| categories.contains(c))
        .map(|(words, c)| (words.as_slice(), c.as_str()));
    let words = scenethesis_words::words(category);
    if let Some(c) = scenethesis_words::nearest_category(&words, rows) {
        return Err(Some(c.to_owned()));
    }
    let spelled = words.join("_");
    Err(categories
        .iter()
        .min_by_key(|c| edit_distance(&spelled, c))
        .cloned())
}

/// The Levenshtein distance of two strings, by characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != *cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// Depth values closer together than this (metres) count as one constant depth.
pub const MIN_DEPTH_SPREAD: f32 = 1e-3;

/// Refuses a depth map whose known values are all the same (within [`MIN_DEPTH_SPREAD`]): it
/// shows no floor, wall or object to place anything by, and fitting objects to it runs for
/// minutes without agreeing. A map with no known value at all is refused too.
pub fn check_depth_varies(depth: &DepthMap) -> Result<(), String> {
    let known = depth.values().iter().filter(|d| d.is_finite() && **d > 0.0);
    let (lo, hi) = known.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), d| {
        (lo.min(*d), hi.max(*d))
    });
    if lo > hi {
        return Err("no pixel has a known depth (every value is 0): expected metric depth of the scene, or leave the depth out".into());
    }
    if hi - lo < MIN_DEPTH_SPREAD {
        return Err(format!(
            "every known pixel has the same depth ({lo} m): expected the varying depth of a scene (floor, walls, objects)"
        ));
    }
    Ok(())
}

/// Decodes a provider's PNG or JPEG answer to the camera's size `[w, h]`: an image of another
/// size with the same aspect ratio (within 1 %) is resampled, any other is refused.
pub fn decode_to_size(bytes: &[u8], size: [u32; 2], what: &str) -> Result<RgbImage, String> {
    let decoded = image::load_from_memory(bytes)
        .map_err(|e| format!("{what}: not a readable PNG or JPEG image ({e})"))?
        .to_rgb8();
    let (w, h) = decoded.dimensions();
    let [cw, ch] = size;
    let decoded = if (w, h) == (cw, ch) {
        decoded
    } else {
        let aspect = |a: u32, b: u32| a as f64 / b.max(1) as f64;
        if (aspect(w, h) / aspect(cw, ch) - 1.0).abs() > 0.01 {
            return Err(format!(
                "{what}: the image is {w} × {h} pixels; expected {cw} × {ch} (the rendered room's size) or the same aspect ratio"
            ));
        }
        image::imageops::resize(&decoded, cw, ch, image::imageops::FilterType::Triangle)
    };
    RgbImage::new(cw, ch, decoded.into_raw()).map_err(|e| format!("{what}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn label_categories_map_onto_the_library_or_offer_the_nearest() {
        let library: BTreeSet<String> = ["sofa", "shelf", "coffee_table", "plant"]
            .map(String::from)
            .into();
        assert_eq!(library_category("sofa", &library), Ok("sofa".into()));
        assert_eq!(library_category("couch", &library), Ok("sofa".into()));
        assert_eq!(
            library_category("Coffee Tables", &library),
            Ok("coffee_table".into())
        );
        assert_eq!(
            library_category("pharmacy shelf", &library),
            Err(Some("shelf".into()))
        );
        assert_eq!(
            library_category("plamt", &library),
            Err(Some("plant".into()))
        );
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn constant_or_unknown_depth_is_refused_and_a_millimetre_of_relief_is_enough() {
        let flat = DepthMap::from_fn(8, 8, |_, _| 2.5);
        assert!(check_depth_varies(&flat)
            .unwrap_err()
            .contains("same depth (2.5 m)"));
        let unknown = DepthMap::from_fn(8, 8, |_, _| 0.0);
        assert!(check_depth_varies(&unknown)
            .unwrap_err()
            .contains("no pixel"));
        let edge = DepthMap::from_fn(8, 8, |x, _| {
            if x == 0 {
                2.5 + 1.01 * MIN_DEPTH_SPREAD
            } else {
                2.5
            }
        });
        assert!(check_depth_varies(&edge).is_ok());
        let under = DepthMap::from_fn(8, 8, |x, _| {
            if x == 0 {
                2.5 + 0.99 * MIN_DEPTH_SPREAD
            } else {
                2.5
            }
        });
        assert!(check_depth_varies(&under).is_err());
    }
}
