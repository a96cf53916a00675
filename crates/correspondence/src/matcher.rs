//! The matcher seam: a rendered view of an asset against the guidance region of its object →
//! matched pixel pairs with confidences, and [`lift`] from pixel pairs to [`Correspondence`]s.

use nalgebra::Point2;
use scenethesis_imagery::{Camera, DepthMap, Mask, RgbImage};

use crate::pair::{Correspondence, PairKind};
use crate::raster::RenderedView;

/// The guidance an object is matched against: the guidance camera, the object's visible mask
/// and the guidance depth of the whole image (so that pixels hidden by nearer objects can be
/// told apart from pixels the object does not cover).
#[derive(Debug, Clone, Copy)]
pub struct TargetRegion<'a> {
    /// The guidance camera.
    pub camera: &'a Camera,
    /// The object's visible pixels in the guidance image.
    pub mask: &'a Mask,
    /// Metric depth of the guidance image, when known (already corrected for any global
    /// scale the guide calibrated).
    pub depth: Option<&'a DepthMap>,
    /// The guidance colour image, for matchers that compare appearance (a dense learned
    /// matcher); shape matchers ignore it.
    pub image: Option<&'a RgbImage>,
}

impl TargetRegion<'_> {
    /// The guidance depth at pixel `(x, y)`, when known.
    pub fn depth_at(&self, x: u32, y: u32) -> Option<f32> {
        self.depth.and_then(|d| d.get(x, y))
    }
}

/// Which residuals a matched pixel pair should feed once lifted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatchKind {
    /// The same physical point: pixel distance and, with depth, point distance.
    Point,
    /// Silhouette agreement only: the pixel distance (no target point).
    Silhouette,
    /// Depth agreement only, along the optical axis at the target pixel.
    Depth,
}

/// One matched pixel pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelMatch {
    /// The pixel of the rendered view (integer pixel; its centre is used).
    pub rendered: [u32; 2],
    /// The matching pixel of the guidance image (sub-pixel; `u` right, `v` down).
    pub target: Point2<f64>,
    /// Confidence in [0, 1].
    pub confidence: f64,
    /// Which residuals the pair should feed.
    pub kind: MatchKind,
}

/// Finds pixel pairs between an asset rendered at its current pose and the guidance region of
/// its object. Implementations never see a GPU: they get plain buffers.
///
/// ```
/// use scenethesis_correspondence::{Matcher, MatchKind, PixelMatch, RenderedView, TargetRegion};
///
/// /// Pairs every covered rendered pixel with the same guidance pixel when the mask holds it.
/// struct SamePixel;
///
/// impl Matcher for SamePixel {
///     fn name(&self) -> &str {
///         "same-pixel"
///     }
///     fn match_view(&self, view: &RenderedView, target: &TargetRegion<'_>) -> Vec<PixelMatch> {
///         let (w, h) = (view.depth.width(), view.depth.height());
///         let mut out = Vec::new();
///         for y in 0..h {
///             for x in 0..w {
///                 let (gx, gy) = view.to_guidance(x, y);
///                 if view.depth.get(x, y).is_some() && target.mask.contains(gx, gy) {
///                     out.push(PixelMatch {
///                         rendered: [x, y],
///                         target: nalgebra::Point2::new(gx as f64 + 0.5, gy as f64 + 0.5),
///                         confidence: 1.0,
///                         kind: MatchKind::Point,
///                     });
///                 }
///             }
///         }
///         out
///     }
/// }
///
/// // A 2 × 2 view at full resolution whose asset covers the top-left pixel, against a mask
/// // holding that pixel and its right neighbour: one pair.
/// let camera = scenethesis_imagery::Camera::look_at(
///     scenethesis_imagery::Intrinsics::from_vertical_fov(2, 2, 1.0),
///     nalgebra::Point3::new(0.0, 1.0, 3.0),
///     nalgebra::Point3::new(0.0, 1.0, 0.0),
///     nalgebra::Vector3::y(),
/// );
/// let view = RenderedView {
///     camera: camera.clone(),
///     offset: [0, 0],
///     stride: 1,
///     pose: Default::default(),
///     depth: scenethesis_imagery::DepthMap::from_fn(2, 2, |x, y| {
///         if (x, y) == (0, 0) { 3.0 } else { f32::NAN }
///     }),
///     color: None,
/// };
/// let mut mask = scenethesis_imagery::Mask::new(2, 2);
/// mask.set(0, 0, true);
/// mask.set(1, 0, true);
/// let target = TargetRegion { camera: &camera, mask: &mask, depth: None, image: None };
/// let pairs = SamePixel.match_view(&view, &target);
/// assert_eq!(pairs.len(), 1);
/// assert_eq!(pairs[0].rendered, [0, 0]);
/// ```
pub trait Matcher: Send + Sync {
    /// A short name for reports.
    fn name(&self) -> &str;

    /// The matched pixel pairs of `view` against `target`.
    fn match_view(&self, view: &RenderedView, target: &TargetRegion<'_>) -> Vec<PixelMatch>;
}

/// Turns pixel pairs into the correspondences the pose-alignment loss consumes: the asset point
/// is the rendered pixel lifted onto the asset's surface (asset frame, scale 1), the target
/// pixel is kept, and the target point is the guidance pixel lifted with the guidance depth
/// (none for silhouette pairs or where the depth is unknown). Pairs whose rendered pixel the
/// asset does not cover are dropped, as are depth pairs without a target depth.
pub fn lift(
    matches: &[PixelMatch],
    view: &RenderedView,
    target: &TargetRegion<'_>,
) -> Vec<Correspondence> {
    matches
        .iter()
        .filter_map(|m| {
            let asset_point = view.asset_point(m.rendered[0], m.rendered[1])?;
            let (tx, ty) = (m.target.x.floor(), m.target.y.floor());
            let depth = if tx >= 0.0 && ty >= 0.0 {
                target.depth_at(tx as u32, ty as u32)
            } else {
                None
            };
            let target_point = match m.kind {
                MatchKind::Silhouette => None,
                MatchKind::Point | MatchKind::Depth => {
                    depth.map(|d| target.camera.unproject(&m.target, d as f64))
                }
            };
            if m.kind == MatchKind::Depth && target_point.is_none() {
                return None;
            }
            Some(Correspondence {
                asset_point,
                target_pixel: m.target,
                target_point,
                confidence: m.confidence.clamp(0.0, 1.0),
                kind: if m.kind == MatchKind::Depth {
                    PairKind::Depth
                } else {
                    PairKind::Point
                },
            })
        })
        .collect()
}
