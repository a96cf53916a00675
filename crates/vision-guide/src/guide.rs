//! [`VisionGuide`]: the [`Guide`] that reads a guidance image.

use std::collections::BTreeMap;
use std::sync::Mutex;

use scenethesis_agents::{
    room_architecture, Adoption, AssetLookup, DroppedObject, Guide, GuideError, GuidedLayout, Plan,
    WalkwayReport,
};
use scenethesis_imagery::{
    Camera, DepthMap, Guidance, Intrinsics, Mask, RgbImage, DEFAULT_VERTICAL_FOV,
};
use scenethesis_models::{
    ChatModel, DepthEstimator, ImageData, ImageEditRequest, ImageGenerator, Segmenter,
};
use scenethesis_scene_graph::{
    holds_under, Architecture, AssetInfo, Material, Mesh, Scene, SupportSurface, SurfaceKind,
};
use scenethesis_vision::{
    lift_scene, LiftOptions, LiftedBox, LiftedScene, SupportGuess, SupportKind,
};

use crate::adopt::{adopted_objects, new_objects, room_size};
use crate::assemble::build_scene;
use crate::camera::estimate_from_floor;
use crate::detect::{ask_boxes, masks_from_boxes, match_labels};
use crate::keep::keep_plan;
use crate::relations::ask_supports;
use scenethesis_render_api::{render_view, RendererError, SceneRenderer, ViewKind, ViewRequest};
use scenethesis_vision::files::Labels;

use crate::source::{decode_to_size, GivenGuidance};

/// Where the guidance image comes from.
enum ImageSource {
    /// Files the user gave, already read and checked.
    Given(Box<GivenGuidance>),
    /// An image model's edit of the plan's empty room, rendered at `size`.
    EditedRender {
        renderer: Box<dyn SceneRenderer>,
        generator: Box<dyn ImageGenerator>,
        size: [u32; 2],
        /// The last edit and the room it was made for: re-plan rounds lay out the same room
        /// (with objects moved or dropped) and reuse it rather than ask for a new picture.
        last: Box<Mutex<Option<Edited>>>,
    },
}

/// An edited room image with its camera, for the room it shows.
#[derive(Clone)]
struct Edited {
    room: Architecture,
    image: RgbImage,
    png: Vec<u8>,
    camera: Camera,
}

/// The vision guide: a guidance image and the plan's objects become the initial scene graph.
///
/// 1. **Image and camera**: the given image (with its `camera.json`), or our render of the
///    plan's empty room edited by an image model into the described scene (the render's
///    camera; re-plan rounds of the same room reuse the edit). A given image without a camera gets one estimated from the floor of its depth
///    ([`crate::camera`]).
/// 2. **Depth**: the given depth map, else the depth model's, else none (single-view
///    metrology under the known camera).
/// 3. **Masks**: the given instance masks matched to the planned objects (by id, else by
///    category), else one box per visible planned object from the vision-language model, made
///    masks by the segmenter (or used as masks; with depth, box pixels on the room's floor or
///    walls are then dropped).
/// 4. **Lift** ([`scenethesis_vision::lift_scene`]) with the retrieved assets' sizes as priors,
///    then the scene graph and 5-DoF poses ([`crate::assemble`]).
///
/// **The image leads** ([`Guide::adopt`], given masks): every labelled object the plan holds no
/// (further) object of its category for is added to the plan before retrieval
/// ([`crate::adopt`]), with its support relation from the image; labels whose category the
/// library cannot map are reported with the nearest category.
///
/// **Planned objects the image does not show** (no mask, or too few 3D points) are left out
/// and reported in [`GuidedLayout::dropped`]; they are never invented, unless
/// [`VisionGuide::with_keep_plan`] asks to place them offline around what the image fixes.
pub struct VisionGuide {
    source: ImageSource,
    vlm: Option<Box<dyn ChatModel>>,
    segmenter: Option<Box<dyn Segmenter>>,
    depth: Option<Box<dyn DepthEstimator>>,
    lift: LiftOptions,
    /// Place the planned objects the image does not show offline around it ([`crate::keep`]).
    keep_plan: bool,
    /// The depth model's estimate of a given image, made once (adoption and every layout
    /// round read the same image).
    estimate: Mutex<Option<DepthMap>>,
}

impl std::fmt::Debug for VisionGuide {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VisionGuide")
            .field("source", &self.source_name())
            .field("vlm", &self.vlm.as_ref().map(|m| m.name()))
            .field("segmenter", &self.segmenter.as_ref().map(|m| m.name()))
            .field("depth", &self.depth.as_ref().map(|m| m.name()))
            .finish_non_exhaustive()
    }
}

fn provider(name: impl Into<String>, message: impl Into<String>) -> GuideError {
    GuideError::Provider {
        provider: name.into(),
        message: message.into(),
    }
}

impl VisionGuide {
    /// A guide reading the given (already checked) guidance files.
    pub fn from_files(given: GivenGuidance) -> Self {
        Self::with_source(ImageSource::Given(Box::new(given)))
    }

    /// A guide that renders the plan's empty room at `size` pixels with `renderer` and has
    /// `generator` edit it into the described scene. Needs a vision-language model
    /// ([`VisionGuide::with_vlm`]) for the objects' boxes.
    pub fn edit_render(
        renderer: impl SceneRenderer + 'static,
        generator: impl ImageGenerator + 'static,
        size: [u32; 2],
    ) -> Self {
        Self::with_source(ImageSource::EditedRender {
            renderer: Box::new(renderer),
            generator: Box::new(generator),
            size,
            last: Box::new(Mutex::new(None)),
        })
    }

    fn with_source(source: ImageSource) -> Self {
        Self {
            source,
            vlm: None,
            segmenter: None,
            depth: None,
            lift: LiftOptions::default(),
            keep_plan: false,
            estimate: Mutex::new(None),
        }
    }

    /// Boxes of the planned objects from this vision-language model (used when no masks are
    /// given), and the support relations it states, cross-checked with the lifted geometry
    /// (always, given masks or not).
    pub fn with_vlm(mut self, vlm: impl ChatModel + 'static) -> Self {
        self.vlm = Some(Box::new(vlm));
        self
    }

    /// Masks from the boxes by this box-prompted segmenter.
    pub fn with_segmenter(mut self, segmenter: impl Segmenter + 'static) -> Self {
        self.segmenter = Some(Box::new(segmenter));
        self
    }

    /// Metric depth from this model when no depth is given.
    pub fn with_depth_estimator(mut self, depth: impl DepthEstimator + 'static) -> Self {
        self.depth = Some(Box::new(depth));
        self
    }

    /// With `keep`, the planned objects the image does not show are placed offline around
    /// what it fixes ([`crate::keep`], `--keep-plan`) instead of being left out.
    pub fn with_keep_plan(mut self, keep: bool) -> Self {
        self.keep_plan = keep;
        self
    }

    /// Lift tuning (priors are set per run from the retrieved assets).
    pub fn with_lift_options(mut self, options: LiftOptions) -> Self {
        self.lift = options;
        self
    }

    fn source_name(&self) -> String {
        match &self.source {
            ImageSource::Given(g) => g.files.image.display().to_string(),
            ImageSource::EditedRender {
                renderer,
                generator,
                ..
            } => format!("{} edited by {}", renderer.name(), generator.name()),
        }
    }

    /// The image, its PNG bytes, the camera (if known), given depth and given masks.
    #[allow(clippy::type_complexity)]
    fn image(
        &self,
        plan: &Plan,
        architecture: &Architecture,
        seed: u64,
    ) -> Result<
        (
            RgbImage,
            Vec<u8>,
            Option<Camera>,
            Option<DepthMap>,
            Option<BTreeMap<String, Mask>>,
            Vec<DroppedObject>,
        ),
        GuideError,
    > {
        match &self.source {
            ImageSource::Given(g) => {
                let (masks, unmatched) = match &g.masks {
                    Some((masks, labels)) => {
                        let (m, u) = match_labels(plan, masks, labels);
                        (Some(m), u)
                    }
                    None => (None, Vec::new()),
                };
                let dropped = unmatched
                    .into_iter()
                    .map(|(id, reason)| DroppedObject { id, reason })
                    .collect();
                Ok((
                    g.image.clone(),
                    g.image_png.clone(),
                    g.camera,
                    g.depth.clone(),
                    masks,
                    dropped,
                ))
            }
            ImageSource::EditedRender {
                renderer,
                generator,
                size,
                last,
            } => {
                let mut last = last.lock().unwrap_or_else(|e| e.into_inner());
                if let Some(e) = last.as_ref().filter(|e| &e.room == architecture) {
                    let e = e.clone();
                    return Ok((e.image, e.png, Some(e.camera), None, None, Vec::new()));
                }
                let (camera, room_image) = render_room(renderer.as_ref(), architecture, *size)
                    .map_err(|e| {
                        provider(format!("room render ({})", renderer.name()), e.to_string())
                    })?;
                let png = room_image.to_png();
                let request = ImageEditRequest {
                    prompt: edit_prompt(plan),
                    image: ImageData::from_bytes(png, "the empty room's render")
                        .expect("PNG bytes"),
                    mask: None,
                    size: *size,
                    seed: Some(seed),
                };
                let edited = generator
                    .edit(&request)
                    .map_err(|e| provider(generator.name(), e.to_string()))?;
                let what = format!("{}: the edited image", generator.name());
                let size = [camera.intrinsics.width, camera.intrinsics.height];
                let image = decode_to_size(&edited.image.bytes, size, &what)
                    .map_err(|e| provider(generator.name(), e))?;
                let png = if edited.image.bytes.len() > 8
                    && (image.width(), image.height()) == (size[0], size[1])
                    && edited.image.format == scenethesis_models::ImageFormat::Png
                {
                    edited.image.bytes.clone()
                } else {
                    image.to_png()
                };
                *last = Some(Edited {
                    room: architecture.clone(),
                    image: image.clone(),
                    png: png.clone(),
                    camera,
                });
                Ok((image, png, Some(camera), None, None, Vec::new()))
            }
        }
    }
}

/// The plan's empty room (floor, walls, door) drawn from the photo view at `size`, the view
/// `preview.png` shows: the camera and the colour image.
fn render_room(
    renderer: &dyn SceneRenderer,
    architecture: &Architecture,
    size: [u32; 2],
) -> Result<(Camera, RgbImage), RendererError> {
    let room = Scene::new(architecture.clone());
    let request = ViewRequest::new(ViewKind::Photo, size);
    let view = render_view(renderer, &room, &BTreeMap::new(), request)?;
    Ok((view.camera, RgbImage::from_rgba(&view.color)))
}

/// What the image model is asked to draw into the empty room.
pub fn edit_prompt(plan: &Plan) -> String {
    let objects: Vec<String> = plan
        .objects
        .iter()
        .map(|o| o.category.replace('_', " "))
        .collect();
    format!(
        "Furnish this empty room into a realistic photograph of a {}: {} It holds: {}. Keep the \
         camera, the walls, the floor, the door and the lighting exactly as they are; only add \
         the furniture and objects, standing on the floor or on each other, fully inside the \
         room.",
        plan.scene_type.replace('_', " "),
        plan.description,
        objects.join(", ")
    )
}

/// Drops box-mask pixels whose depth puts them on the room's structure: the floor (unless the
/// object is itself flat, under 10 cm) or behind a wall's inner face. Used only for masks that
/// are plain boxes.
fn subtract_room(
    mask: &Mask,
    camera: &Camera,
    depth: &DepthMap,
    architecture: &Architecture,
    flat: bool,
) -> Mask {
    let floor = &architecture.floor;
    let indoor = !architecture.walls.is_empty();
    let mut out = mask.clone();
    for (u, v) in mask.pixels() {
        let Some(z) = depth.get(u, v) else {
            continue;
        };
        let p = camera.unproject(
            &nalgebra::Point2::new(u as f64 + 0.5, v as f64 + 0.5),
            z as f64,
        );
        let on_floor = !flat && p.y < 0.03;
        let m = 0.04;
        let on_wall = indoor
            && (p.x < floor.min.x + m
                || p.x > floor.max.x - m
                || p.z < floor.min.y + m
                || p.z > floor.max.y - m);
        if on_floor || on_wall {
            out.set(u, v, false);
        }
    }
    out
}

impl Guide for VisionGuide {
    fn name(&self) -> &str {
        "vision"
    }

    /// Every labelled mask of given guidance that no planned object of its category is left
    /// for becomes a new planned object ([`crate::adopt`]); the labels the library could not map
    /// are handed on for the report. Boxes of a vision-language model name planned objects only
    /// (nothing is adopted from them yet).
    fn adopt(&self, plan: &Plan, _seed: u64) -> Result<Adoption, GuideError> {
        let ImageSource::Given(g) = &self.source else {
            return Ok(Adoption::default());
        };
        let mut adoption = Adoption {
            unmapped: g.unmapped.clone(),
            notes: g.notes.clone(),
            ..Adoption::default()
        };
        let no_masks = (BTreeMap::new(), Labels::new());
        let (masks, labels) = g.masks.as_ref().unwrap_or(&no_masks);
        let (new, notes) = new_objects(plan, masks, labels);
        adoption.notes.extend(notes);
        if new.is_empty() && g.depth.is_none() && self.depth.is_none() {
            return Ok(adoption);
        }
        let architecture = room_architecture(plan)?;
        let (w, h) = (g.image.width(), g.image.height());
        let image_data = ImageData::from_bytes(g.image_png.clone(), "the guidance image")
            .map_err(|e| provider("guidance image", e.to_string()))?;
        let depth = match &g.depth {
            Some(d) => Some(d.clone()),
            None => self.estimated_depth(&image_data, g.camera, (w, h))?,
        };
        let camera = match g.camera {
            Some(c) => c,
            None => camera_from_floor(depth.as_ref(), (w, h), &architecture)?,
        };
        let view = Guidance::new(camera, g.image.clone(), depth, masks.clone())
            .map_err(|e| provider("guidance", e.to_string()))?;
        // The room as the image shows it, when a camera placed in the room says where its
        // walls are — unless its walls are given (a house room's are the floor plan's).
        if g.camera.is_some() && !plan.room_is_fixed() {
            if let Some(size) = room_size(plan, &view) {
                adoption.notes.push(format!(
                    "the room measured from the walls the guidance image shows: {:.2} × {:.2} m \
                     (the plan had {:.2} × {:.2} m)",
                    size[0], size[1], plan.room_size[0], plan.room_size[1]
                ));
                adoption.room_size = Some(size);
            }
        }
        if masks.is_empty() {
            return Ok(adoption);
        }
        let room = adoption.apply(plan);
        let architecture = room_architecture(&room)?;
        let (objects, sizes) =
            adopted_objects(plan, &new, &view, labels, &architecture, &self.lift)
                .map_err(|e| provider("lift", e))?;
        adoption.objects = objects;
        adoption.sizes = sizes;
        if new.is_empty() {
            return Ok(adoption);
        }
        let listed: Vec<String> = new
            .iter()
            .map(|n| format!("`{}` ({})", n.id, n.category))
            .collect();
        adoption.notes.push(format!(
            "adopted from the guidance image: {} labelled object(s) the plan did not hold: {}",
            new.len(),
            listed.join(", ")
        ));
        Ok(adoption)
    }

    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        let architecture = room_architecture(plan)?;
        let infos = asset_infos(plan, assets)?;
        let (image, png, camera, given_depth, given_masks, mut dropped) =
            self.image(plan, &architecture, seed)?;
        let (w, h) = (image.width(), image.height());
        let image_data = ImageData::from_bytes(png, "the guidance image")
            .map_err(|e| provider("guidance image", e.to_string()))?;
        let depth = match given_depth {
            Some(d) => Some(d),
            None => self.estimated_depth(&image_data, camera, (w, h))?,
        };
        let camera = match camera {
            Some(c) => c,
            None => camera_from_floor(depth.as_ref(), (w, h), &architecture)?,
        };
        scenethesis_vision::metrology::check_camera(&camera)
            .map_err(|e| provider("camera", e.to_string()))?;
        let masks = match given_masks {
            Some(m) => m,
            None => {
                let seen = Seen {
                    image: &image_data,
                    size: (w, h),
                    camera: &camera,
                    depth: depth.as_ref(),
                    architecture: &architecture,
                    infos: &infos,
                };
                self.boxed_masks(plan, &seen, seed, &mut dropped)?
            }
        };
        let guidance = Guidance::new(camera, image, depth, masks)
            .map_err(|e| provider("guidance", e.to_string()))?;
        let options = self.lift_options(&infos, &guidance, &architecture);
        let mut lifted =
            lift_scene(&guidance, &options).map_err(|e| provider("lift", e.to_string()))?;
        let mut notes =
            self.cross_check_supports(plan, &mut lifted, &options, &image_data, seed)?;
        rest_where_the_holder_rests(&mut lifted.supports, &infos);
        rest_on_nearest_surface(&mut lifted.supports, &lifted.boxes, &infos);
        let mut left_out = unplaced(plan, &lifted);
        if lifted.boxes.is_empty() {
            return Err(provider(
                "vision guide",
                format!(
                    "none of the {} planned objects was found in the guidance image",
                    plan.objects.len()
                ),
            ));
        }
        let mut scene = build_scene(
            plan,
            seed,
            architecture,
            &infos,
            &lifted.boxes,
            &lifted.supports,
            camera.position,
        );
        if self.keep_plan && !left_out.is_empty() {
            let (kept, unkept) = keep_plan(&mut scene, plan, &infos, seed);
            if !kept.is_empty() {
                notes.push(format!(
                    "--keep-plan: {} planned object(s) the image does not show placed offline \
                     around it: {}",
                    kept.len(),
                    kept.join(", ")
                ));
            }
            left_out = unkept;
        }
        dropped.extend(left_out);
        let walkway = walkway(&scene, &infos);
        Ok(GuidedLayout {
            scene,
            dropped,
            walkway,
            guidance: Some(guidance),
            notes,
        })
    }
}

/// What the masks of a guidance image are cut against: the image, its size, the camera, the
/// depth (if any), the room and the planned objects' asset metadata.
struct Seen<'a> {
    image: &'a ImageData,
    size: (u32, u32),
    camera: &'a Camera,
    depth: Option<&'a DepthMap>,
    architecture: &'a Architecture,
    infos: &'a BTreeMap<String, AssetInfo>,
}

impl VisionGuide {
    /// The depth model's depth of the image, checked to have the image's size; `None`
    /// without a depth model.
    fn estimated_depth(
        &self,
        image: &ImageData,
        camera: Option<Camera>,
        (w, h): (u32, u32),
    ) -> Result<Option<DepthMap>, GuideError> {
        let Some(model) = &self.depth else {
            return Ok(None);
        };
        let given = matches!(self.source, ImageSource::Given(_));
        let mut cached = self.estimate.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(d) = cached.as_ref().filter(|_| given) {
            return Ok(Some(d.clone()));
        }
        let d = model
            .estimate(image, camera.map(|c| c.intrinsics))
            .map_err(|e| provider(model.name(), e.to_string()))?
            .depth;
        if (d.width(), d.height()) != (w, h) {
            return Err(provider(
                model.name(),
                format!(
                    "the depth map is {} × {}; expected the guidance image's {w} × {h}",
                    d.width(),
                    d.height()
                ),
            ));
        }
        if given {
            *cached = Some(d.clone());
        }
        Ok(Some(d))
    }

    /// Masks from the VLM's boxes of the planned objects: segmented when a segmenter is set,
    /// else the boxes themselves with the room's floor and walls cut away (by the depth).
    /// Boxes the answer could not use are noted in `dropped`.
    fn boxed_masks(
        &self,
        plan: &Plan,
        seen: &Seen<'_>,
        seed: u64,
        dropped: &mut Vec<DroppedObject>,
    ) -> Result<BTreeMap<String, Mask>, GuideError> {
        let Some(vlm) = &self.vlm else {
            return Err(provider(
                "vision guide",
                "no masks: give --guide-masks ids.png with --guide-labels labels.json, \
                 or a vision-language model (--vlm-model) to box the objects",
            ));
        };
        let (boxes, notes) = ask_boxes(vlm.as_ref(), plan, seen.image.clone(), seed)
            .map_err(|e| provider(vlm.name(), e))?;
        for (id, note) in notes {
            dropped.push(DroppedObject {
                id,
                reason: format!("{}: {note}", vlm.name()),
            });
        }
        let seg = self
            .segmenter
            .as_ref()
            .map(|s| (s.as_ref() as &dyn Segmenter, seen.image));
        let (w, h) = seen.size;
        let mut masks = masks_from_boxes(&boxes, w, h, seg).map_err(|e| {
            provider(
                self.segmenter
                    .as_ref()
                    .map_or("box masks".into(), |s| s.name()),
                e,
            )
        })?;
        if self.segmenter.is_none() {
            if let Some(d) = seen.depth {
                for (id, m) in masks.iter_mut() {
                    let flat = seen.infos[id].size[1] < 0.1;
                    *m = subtract_room(m, seen.camera, d, seen.architecture, flat);
                }
            }
        }
        Ok(masks)
    }

    /// The lift's options with each masked object's asset size as its prior and the room's
    /// walls (a box hanging on a wall is put against it).
    fn lift_options(
        &self,
        infos: &BTreeMap<String, AssetInfo>,
        guidance: &Guidance,
        architecture: &Architecture,
    ) -> LiftOptions {
        let mut options = self.lift.clone();
        options.priors = infos
            .iter()
            .filter(|(id, _)| guidance.masks.contains_key(*id))
            .map(|(id, i)| {
                let [x, y, z] = i.size.map(f64::from);
                (id.clone(), nalgebra::Vector3::new(x, y, z))
            })
            .collect();
        options.tiers = infos
            .iter()
            .filter(|(id, i)| guidance.masks.contains_key(*id) && i.size[1] > 0.0)
            .map(|(id, i)| (id.clone(), tiers(i)))
            .filter(|(_, t)| !t.is_empty())
            .collect();
        options.walls = architecture.walls.clone();
        options
    }

    /// The model's support relations, cross-checked with the lift's: where the geometry is
    /// ambiguous the model decides, where they clearly disagree the geometry is kept and the
    /// disagreement noted. Nothing changes without a VLM or without lifted boxes.
    fn cross_check_supports(
        &self,
        plan: &Plan,
        lifted: &mut LiftedScene,
        options: &LiftOptions,
        image: &ImageData,
        seed: u64,
    ) -> Result<Vec<String>, GuideError> {
        let mut notes = Vec::new();
        let Some(vlm) = self.vlm.as_ref().filter(|_| !lifted.boxes.is_empty()) else {
            return Ok(notes);
        };
        let objects: Vec<(&str, &str)> = lifted
            .boxes
            .iter()
            .filter_map(|b| plan.object(&b.id))
            .map(|o| (o.id.as_str(), o.category.as_str()))
            .collect();
        let (stated, skipped) = ask_supports(vlm.as_ref(), plan, &objects, image.clone(), seed)
            .map_err(|e| provider(vlm.name(), e))?;
        for (id, why) in skipped {
            notes.push(format!("{}: support of `{id}` ignored: {why}", vlm.name()));
        }
        for check in lifted.cross_check(&stated, options) {
            notes.push(format!("{}: {}", vlm.name(), check.note()));
        }
        Ok(notes)
    }
}

/// Surfaces within this many metres of each other's height are one board (the bays of a
/// shelving unit divided by uprights).
const TIER_BAND: f32 = 0.01;

/// The heights of an asset's shelves and inner floors that span at least half its footprint
/// together at one height (boards, bays side by side, not a drawer's floor), as fractions of
/// its height.
fn tiers(info: &AssetInfo) -> Vec<f64> {
    let footprint = info.size[0] * info.size[2];
    let mut levels: Vec<(f32, f32)> = Vec::new();
    let mut boards: Vec<_> = info
        .support_surfaces
        .iter()
        .filter(|s| matches!(s.kind, SurfaceKind::Shelf | SurfaceKind::Interior))
        .collect();
    boards.sort_by(|a, b| a.height.total_cmp(&b.height));
    for s in boards {
        match levels.last_mut() {
            Some((h, area)) if s.height - *h <= TIER_BAND => *area += s.area(),
            _ => levels.push((s.height, s.area())),
        }
    }
    levels
        .into_iter()
        .filter(|&(_, area)| area >= 0.5 * footprint)
        .map(|(h, _)| f64::from(h / info.size[1]))
        .collect()
}

/// A box lifted *on* or *inside* a parent whose asset holds nothing (no support surface: a
/// can found on top of a bottle, from a few pixels over its rim) rests where that parent
/// rests instead — inside the rack the bottle stands in, or on the floor.
fn rest_where_the_holder_rests(supports: &mut [SupportGuess], infos: &BTreeMap<String, AssetInfo>) {
    let holds_nothing = |id: &str| {
        infos
            .get(id)
            .is_some_and(|info| info.support_surfaces.is_empty())
    };
    let guesses: BTreeMap<String, SupportGuess> =
        supports.iter().map(|g| (g.id.clone(), g.clone())).collect();
    for guess in supports
        .iter_mut()
        .filter(|g| matches!(g.kind, SupportKind::On | SupportKind::Inside))
    {
        // Up the chain while the holder holds nothing (a chain is at most as long as the
        // guesses; lifted parents are strictly lower, so it ends).
        for _ in 0..guesses.len() {
            let Some(parent) = guess.parent.clone().filter(|p| holds_nothing(p)) else {
                break;
            };
            match guesses.get(&parent) {
                Some(up) if matches!(up.kind, SupportKind::On | SupportKind::Inside) => {
                    guess.parent = up.parent.clone();
                    guess.kind = up.kind;
                }
                _ => {
                    guess.parent = None;
                    guess.kind = SupportKind::Ground;
                    break;
                }
            }
        }
    }
}

/// A box lifted *under* a parent whose asset has no space beneath it (a display case standing
/// on its plinth, whose box came out wide through its glass) stands on the floor. A box
/// lifted *inside* a parent rests *on* it instead when the parent's asset has nothing to
/// be inside of (no shelf, no inner floor: a towel on a camping chair's sling, its bottom
/// found below the sling's rim), or when the surface nearest its bottom is a top (a mug on a
/// workbench whose pegboard makes the bench's box tall, not on the bench's low shelf).
/// Surface heights are the asset's, scaled to the parent box's height.
fn rest_on_nearest_surface(
    supports: &mut [SupportGuess],
    boxes: &[LiftedBox],
    infos: &BTreeMap<String, AssetInfo>,
) {
    let by_id: BTreeMap<&str, &LiftedBox> = boxes.iter().map(|b| (b.id.as_str(), b)).collect();
    for guess in supports.iter_mut().filter(|g| g.kind == SupportKind::Under) {
        let open = guess
            .parent
            .as_deref()
            .and_then(|p| infos.get(p))
            .is_none_or(|info| holds_under(&info.support_surfaces));
        if !open {
            guess.parent = None;
            guess.kind = SupportKind::Ground;
        }
    }
    for guess in supports
        .iter_mut()
        .filter(|g| g.kind == SupportKind::Inside)
    {
        let Some(parent) = guess.parent.as_deref() else {
            continue;
        };
        let (Some(info), Some(b)) = (infos.get(parent), by_id.get(guess.id.as_str())) else {
            continue;
        };
        let nearest = by_id.get(parent).and_then(|p| {
            let scale = (p.top() - p.bottom()) / f64::from(info.size[1]).max(1e-6);
            info.support_surfaces.iter().min_by(|x, y| {
                let gap = |s: &&SupportSurface| {
                    (p.bottom() + f64::from(s.height) * scale - b.bottom()).abs()
                };
                gap(x).total_cmp(&gap(y))
            })
        });
        let hollow = info
            .support_surfaces
            .iter()
            .any(|s| matches!(s.kind, SurfaceKind::Shelf | SurfaceKind::Interior));
        if !hollow || nearest.is_some_and(|s| s.kind == SurfaceKind::Top) {
            guess.kind = SupportKind::On;
        }
    }
}

/// Each planned object's asset metadata, by id; an object without an asset is an error.
fn asset_infos(
    plan: &Plan,
    assets: &dyn AssetLookup,
) -> Result<BTreeMap<String, AssetInfo>, GuideError> {
    let mut infos = BTreeMap::new();
    for o in &plan.objects {
        let info = assets
            .asset_info(o)
            .ok_or_else(|| GuideError::MissingAsset {
                id: o.id.clone(),
                category: o.category.clone(),
            })?;
        infos.insert(o.id.clone(), info);
    }
    Ok(infos)
}

/// The camera estimated from the floor of `depth` with the default field of view; without
/// depth there is nothing to estimate it from.
fn camera_from_floor(
    depth: Option<&DepthMap>,
    (w, h): (u32, u32),
    architecture: &Architecture,
) -> Result<Camera, GuideError> {
    let Some(depth) = depth else {
        return Err(provider(
            "camera",
            "the guidance image has no camera: give --camera camera.json, or depth \
             (--guide-depth or a depth model) to estimate it from the floor",
        ));
    };
    let k = Intrinsics::from_vertical_fov(w, h, DEFAULT_VERTICAL_FOV);
    estimate_from_floor(depth, k, architecture)
        .map_err(|e| provider("camera estimate from the floor", e))
}

/// The planned objects the lift did not place, with why.
fn unplaced(plan: &Plan, lifted: &LiftedScene) -> Vec<DroppedObject> {
    plan.objects
        .iter()
        .filter(|o| !lifted.boxes.iter().any(|b| b.id == o.id))
        .map(|o| {
            let reason = if lifted.missing.contains(&o.id) {
                "its mask in the guidance image gave too few 3D points to place it"
            } else {
                "not found in the guidance image (no mask)"
            };
            DroppedObject {
                id: o.id.clone(),
                reason: reason.into(),
            }
        })
        .collect()
}

/// Walk and reach of the guided floor by the metric's raster rules, with each object as its
/// asset's box; the door counts as reachable when the floor just inside it is free (no box
/// footprint within the robot radius of the point 40 cm inside the opening).
fn walkway(scene: &Scene, infos: &BTreeMap<String, AssetInfo>) -> WalkwayReport {
    use scenethesis_eval::raster::walk_and_reach;
    use scenethesis_eval::{EvalObject, EvalScene};
    let objects = scene
        .objects
        .iter()
        .map(|o| {
            let [sx, sy, sz] = infos[&o.id].size;
            let mesh = Mesh::cuboid(
                o.id.clone(),
                Material::new("box", [0.5, 0.5, 0.5], 0.5),
                [-sx / 2.0, 0.0, -sz / 2.0],
                [sx / 2.0, sy, sz / 2.0],
            );
            EvalObject::from_scene_object(o, &mesh)
        })
        .collect();
    let eval = EvalScene {
        objects,
        architecture: scene.architecture.clone(),
    };
    let wr = walk_and_reach(&eval);
    let door_reachable = scene.architecture.doors.iter().all(|d| {
        let Some(wall) = scene.architecture.wall(&d.wall) else {
            return true;
        };
        let along = (wall.end - wall.start).normalize();
        let at = wall.start + along * d.offset;
        let floor = &scene.architecture.floor;
        let centre = nalgebra::center(&floor.min, &floor.max);
        let inward = (centre - at).normalize();
        let p = at + inward * 0.4;
        eval.objects.iter().filter(|o| o.on_ground()).all(|o| {
            let b = o.aabb();
            let r = 0.2;
            !(p.x > b.min.x - r && p.x < b.max.x + r && p.y > b.min.z - r && p.y < b.max.z + r)
        })
    });
    WalkwayReport {
        walk_ratio: wr.walk,
        door_reachable,
        unreachable: wr.unreachable_floor_objects,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::{AssetRef, Placement};

    fn info(surfaces: &[(SurfaceKind, f32)]) -> AssetInfo {
        AssetInfo {
            source: AssetRef::Procedural {
                generator: "workbench".into(),
                seed: 0,
                look: Default::default(),
            },
            category: "workbench".into(),
            synonyms: Vec::new(),
            size: [1.6, 1.8, 0.6],
            placement: Placement::Floor,
            front: [0.0, 0.0, 1.0],
            support_surfaces: surfaces
                .iter()
                .enumerate()
                .map(|(k, &(kind, height))| SupportSurface {
                    name: format!("s{k}"),
                    kind,
                    polygon: vec![[-0.7, -0.25], [0.7, -0.25], [0.7, 0.25], [-0.7, 0.25]],
                    height,
                    clearance: None,
                })
                .collect(),
            scale_range: [0.8, 1.2],
            joints: Vec::new(),
            opening_bounds: None,
        }
    }

    fn inside(id: &str) -> SupportGuess {
        SupportGuess {
            id: id.into(),
            parent: Some("bench".into()),
            kind: SupportKind::Inside,
        }
    }

    #[test]
    fn inside_a_box_becomes_on_the_top_nearest_its_bottom_or_a_hollowless_parent() {
        // A workbench with a pegboard (1.8 m), its top at 0.9 m and a low shelf at 0.25 m.
        let bench = LiftedBox::axis_aligned("bench", [0.0, 0.9, 0.0], [0.8, 0.9, 0.3]);
        let mug = LiftedBox::axis_aligned("mug", [0.2, 0.95, 0.0], [0.05, 0.05, 0.05]);
        let paint = LiftedBox::axis_aligned("paint", [-0.2, 0.34, 0.0], [0.08, 0.09, 0.08]);
        let boxes = [bench, mug, paint];
        let mut infos = BTreeMap::new();
        infos.insert(
            "bench".to_string(),
            info(&[(SurfaceKind::Top, 0.9), (SurfaceKind::Shelf, 0.25)]),
        );
        let mut supports = vec![inside("mug"), inside("paint")];
        rest_on_nearest_surface(&mut supports, &boxes, &infos);
        assert_eq!(supports[0].kind, SupportKind::On, "the mug is on the top");
        assert_eq!(
            supports[1].kind,
            SupportKind::Inside,
            "the can is on the shelf"
        );
        // Nothing to be inside of: on it, wherever its bottom came out; nothing to stand
        // under: on the floor.
        infos.insert("bench".to_string(), info(&[(SurfaceKind::Top, 0.9)]));
        let mut under = inside("paint");
        under.kind = SupportKind::Under;
        let mut supports = vec![inside("paint"), under];
        rest_on_nearest_surface(&mut supports, &boxes, &infos);
        assert_eq!(supports[0].kind, SupportKind::On);
        let floor = (supports[1].kind, supports[1].parent.as_deref());
        assert_eq!(floor, (SupportKind::Ground, None));
    }

    #[test]
    fn on_a_thing_that_holds_nothing_is_where_that_thing_rests() {
        let mut infos = BTreeMap::new();
        infos.insert("rack".to_string(), info(&[(SurfaceKind::Shelf, 0.1)]));
        infos.insert("bottle".to_string(), info(&[]));
        infos.insert("stool".to_string(), info(&[]));
        let guess = |id: &str, parent: Option<&str>, kind| SupportGuess {
            id: id.into(),
            parent: parent.map(str::to_owned),
            kind,
        };
        let mut supports = vec![
            guess("bottle", Some("rack"), SupportKind::Inside),
            guess("can", Some("bottle"), SupportKind::On),
            guess("stool", None, SupportKind::Ground),
            guess("cup", Some("stool"), SupportKind::On),
        ];
        rest_where_the_holder_rests(&mut supports, &infos);
        let of = |k: usize| (supports[k].kind, supports[k].parent.as_deref());
        assert_eq!(of(1), (SupportKind::Inside, Some("rack")));
        assert_eq!(of(3), (SupportKind::Ground, None));
        assert_eq!(of(0), (SupportKind::Inside, Some("rack")));
    }
}
